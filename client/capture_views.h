// SelectCaptureViews: the views to enroll from a walk around an object. The circle
// of azimuths is cut into steps (default 5 degrees, COIL-100's spacing; step k holds azimuths
// [k * step, (k + 1) * step) of the device's compass); each step keeps its sharpest usable
// frame, so a walk that lingers gives one view per step and a fast one leaves steps empty,
// which the report shows.
//
// Usable (client/frame_quality.h, IsUsableFrame): tracked (not lost), not too noisy, and not far
// less sharp than the capture's median frame. A step whose sharpest frame is blurred gets no
// view: a blurred view would describe the blur.
// Thread safety: none (reads the capture).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "client/capture_reader.h"
#include "client/enrollment_image.h"
#include "client/frame_quality.h"
#include "core/model/azimuth_gaps.h"

namespace orbit {

inline constexpr double kDefaultEnrollmentStepDeg = 5;

struct CaptureViewOptions {
  double step_deg = kDefaultEnrollmentStepDeg;  // in (0, 180]
  FrameQualityLimits quality = {};
  // Called after each frame read with the frames read so far and the capture's frame count
  // (0 when unknown).
  std::function<void(long read, long total)> progress;
};

// One frame chosen as a view.
struct CaptureView {
  long frame_index = 0;
  cv::Rect region;  // the object's region in that frame
  FrameQuality quality;
  EnrollmentImage image;  // the region's pixels (a copy), the frame's azimuth and elevation
};

// What one step of the circle got from the capture: the frame kept, or why none was. The
// frames are counted by the azimuth the log gives them, tracked or not.
struct CaptureStep {
  double from_deg = 0;  // the step holds azimuths [from_deg, to_deg)
  double to_deg = 0;
  long frames = 0;  // frames whose azimuth fell in the step
  long lost = 0;    // ... whose object the tracker had lost
  long noisy = 0;   // ... too noisy
  // The view kept: its position in CaptureViewSelection::views. None when the step had no
  // frame, when every frame was lost or too noisy, or else when its sharpest other frame was
  // too blurred (below the capture's usable sharpness: so were all of them).
  std::optional<std::size_t> view;
};

struct CaptureViewSelection {
  std::vector<CaptureView> views;  // in frame order
  long frames_read = 0;
  long frames_lost = 0;      // tracking lost
  long frames_unusable = 0;  // too noisy, or too blurred (only those that would have been chosen
                             // count as blurred: a step's sharper frame may have replaced them)
  int steps_total = 0;       // 360 / step, rounded up
  std::vector<CaptureStep> steps;  // steps_total of them, from azimuth 0 up
  // The arcs between the views kept (their azimuths, circularly) wider than the step: a view
  // may lie anywhere in its step, so views in neighbouring steps can be up to two steps apart,
  // and an empty step widens the arc further (core/model/azimuth_gaps.h).
  std::vector<AzimuthGap> gaps;
};

// Reads `capture` to its end and chooses the views. Throws std::invalid_argument for a step
// outside (0, 180], and as CaptureReader::Next.
CaptureViewSelection SelectCaptureViews(CaptureReader& capture,
                                        const CaptureViewOptions& options = {});

}  // namespace orbit
