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
#include <vector>

#include "client/capture_reader.h"
#include "client/enrollment_image.h"
#include "client/frame_quality.h"

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

struct CaptureViewSelection {
  std::vector<CaptureView> views;  // in frame order
  long frames_read = 0;
  long frames_lost = 0;      // tracking lost
  long frames_unusable = 0;  // too noisy, or too blurred (only those that would have been chosen
                             // count as blurred: a step's sharper frame may have replaced them)
  int steps_total = 0;       // 360 / step, rounded up
};

// Reads `capture` to its end and chooses the views. Throws std::invalid_argument for a step
// outside (0, 180], and as CaptureReader::Next.
CaptureViewSelection SelectCaptureViews(CaptureReader& capture,
                                        const CaptureViewOptions& options = {});

}  // namespace orbit
