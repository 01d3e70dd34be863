// ObjectTracker: follows the object through a capture from the box the user drew on the first
// frame, so that each frame's descriptor is computed on the object and not on the whole scene
// (the thesis' field test did the same with CamShift).
//
// Trackers (built on Debian 12's OpenCV 4.6; measured in docs/results/capture.md on generated
// walks, tests/client/object_tracker_test.cc):
// - kTemplate, the default (kDefaultTracker): normalised grey template matching on a frame
//   reduced around the last box, at the first box's size, the template following the object's
//   appearance, checked against its colours (docs/design.md#object-tracking). Its cost follows
//   the template's size, not the frame's: within a phone's budget at video rate. Where the
//   object turns into views unlike the last matched one it reports frames lost rather than
//   follow the background.
// - kCsrt: the discriminative correlation filter with channel and spatial reliability
//   (Lukezic et al., CVPR 2017; opencv_contrib's tracking module). It follows the object's
//   appearance, texture included, and holds on longer in clutter, at many times the cost.
// - kKcf: kernelised correlation filter (Henriques et al., TPAMI 2015): cheaper on small boxes,
//   as close when it holds, but it loses the object on some frames.
// - kCamShift: mean shift on the hue back-projection of the first box (Bradski 1998; the video
//   module). Cheapest, but it follows colour alone and drifts onto background of the object's
//   colours.
//
// Lost: a frame is reported lost, and must not be described, when the tracker says its match
// failed (for the template a correlation or colour match too weak; for CSRT a peak-to-sidelobe
// ratio under 0.07; for CamShift a back-projection with too little of the object's colours),
// when the region found no longer looks like the last matched one (CSRT, KCF: grey correlation
// under 0.25 - the camera turned away, or the tracker jumped to the background), or when less
// than half of the box lies inside the frame (the object is leaving the view). After a loss the
// tracker retries each frame from the last matched frame and box, and reports found again when
// the object is still near it.
//
// Thread safety: none; one tracker per capture, fed its frames in order.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace orbit {

enum class TrackerKind { kTemplate, kCsrt, kKcf, kCamShift };
inline constexpr TrackerKind kTrackerKinds[] = {TrackerKind::kTemplate, TrackerKind::kCsrt,
                                                TrackerKind::kKcf, TrackerKind::kCamShift};
// The tracker of a capture that names none: within a phone's budget per frame
// (docs/design.md#object-tracking).
inline constexpr TrackerKind kDefaultTracker = TrackerKind::kTemplate;

// "template", "csrt", "kcf", "camshift": the names of `--tracker`, written once.
std::string_view TrackerName(TrackerKind kind);
// One line on what the tracker does and costs, for --help.
std::string_view TrackerSummary(TrackerKind kind);
// Throws std::invalid_argument naming the allowed names.
TrackerKind ParseTrackerName(std::string_view name);

struct TrackedBox {
  cv::Rect box;       // the object's box, clipped to the frame; empty when lost off the frame
  bool lost = false;  // true: the tracker lost the object on this frame; do not describe `box`
};

class ObjectTracker {
 public:
  // Starts tracking the object in `box` of `first_frame` (8-bit BGR or grey). Throws
  // std::invalid_argument when the frame is empty or the box is not inside it or smaller than
  // 8 x 8 pixels.
  ObjectTracker(const cv::Mat& first_frame, const cv::Rect& box,
                TrackerKind kind = kDefaultTracker);
  ~ObjectTracker();
  ObjectTracker(const ObjectTracker&) = delete;
  ObjectTracker& operator=(const ObjectTracker&) = delete;

  // Follows the object into the next frame (the same size as the first).
  TrackedBox Track(const cv::Mat& frame);

  TrackerKind kind() const { return kind_; }

  class Impl;  // the tracking algorithm, defined in object_tracker.cc

 private:
  const TrackerKind kind_;
  std::unique_ptr<Impl> impl_;
};

// Intersection over union of two boxes, in [0, 1]; 0 when either is empty.
double IntersectionOverUnion(const cv::Rect& a, const cv::Rect& b);

}  // namespace orbit
