#include "client/object_tracker.h"

#include <functional>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>

namespace orbit {
namespace {

constexpr int kMinBoxSide = 8;  // pixels: smaller boxes hold too little to follow or describe
// Less than this fraction of the tracked box inside the frame: the object is leaving the view.
constexpr double kMinVisibleFraction = 0.5;
// CSRT: lost when the correlation's peak-to-sidelobe ratio is below this (OpenCV's default,
// 0.035, never lost the object on a scene without it; 0.065 to 0.08 kept every frame of the
// generated walks and dropped the other scene; 0.09 lost frames of the walks).
constexpr float kCsrtMinPeakToSidelobe = 0.07f;
// A match (OpenCvTracker) counts when its region correlates at least this well with the last
// matched region, both reduced to kPatchSide x kPatchSide grey pixels. Measured on generated
// walks: 0.37 the least between consecutive frames (most above 0.6), -0.05 when the camera
// turned to a scene without the object.
constexpr double kMinMatchCorrelation = 0.25;
constexpr int kPatchSide = 24;
// CamShift: lost when the window's mean back-projection falls below this fraction of the first
// box's (the object's colours are no longer there).
constexpr double kMinCamShiftEvidence = 0.3;

cv::Mat AsBgr(const cv::Mat& frame) {
  if (frame.channels() == 3) return frame;
  cv::Mat bgr;
  cv::cvtColor(frame, bgr, frame.channels() == 4 ? cv::COLOR_BGRA2BGR : cv::COLOR_GRAY2BGR);
  return bgr;
}

}  // namespace

std::string_view TrackerName(TrackerKind kind) {
  switch (kind) {
    case TrackerKind::kCsrt: return "csrt";
    case TrackerKind::kKcf: return "kcf";
    case TrackerKind::kCamShift: return "camshift";
  }
  return "?";
}

TrackerKind ParseTrackerName(std::string_view name) {
  std::string names;
  for (TrackerKind kind : kTrackerKinds) {
    if (name == TrackerName(kind)) return kind;
    names += (names.empty() ? "" : ", ") + std::string(TrackerName(kind));
  }
  throw std::invalid_argument("unknown tracker '" + std::string(name) + "': expected " + names);
}

double IntersectionOverUnion(const cv::Rect& a, const cv::Rect& b) {
  const double overlap = (a & b).area();
  const double joint = a.area() + b.area() - overlap;
  return joint > 0 ? overlap / joint : 0.0;
}

class ObjectTracker::Impl {
 public:
  virtual ~Impl() = default;
  // The tracker's box in `frame` (unclipped) and whether its match held.
  virtual bool Update(const cv::Mat& bgr, cv::Rect& box) = 0;
};

namespace {

// OpenCV's Tracker interface (CSRT, KCF).
// The normalised correlation of the grey content of box `a` in frame `a_frame` and box `b` in
// `b_frame`, both reduced to kPatchSide squared pixels: about 1 for the same view, about 0 for
// unrelated content.
double PatchCorrelation(const cv::Mat& a_frame, const cv::Rect& a, const cv::Mat& b_frame,
                        const cv::Rect& b) {
  auto patch = [](const cv::Mat& frame, const cv::Rect& box) {
    cv::Mat grey, small;
    cv::cvtColor(frame(box & cv::Rect(0, 0, frame.cols, frame.rows)), grey, cv::COLOR_BGR2GRAY);
    cv::resize(grey, small, cv::Size(kPatchSide, kPatchSide), 0, 0, cv::INTER_AREA);
    return small;
  };
  cv::Mat score;
  cv::matchTemplate(patch(a_frame, a), patch(b_frame, b), score, cv::TM_CCOEFF_NORMED);
  return score.at<float>(0, 0);
}

// OpenCV's Tracker interface (CSRT, KCF), with two guards:
// - A match counts only when the region found still looks like the last matched one
//   (PatchCorrelation at least kMinMatchCorrelation). Between consecutive frames of a walk the
//   object turns a few degrees and the correlation stays high; a tracker that jumped to
//   background, or a camera that turned away, breaks it.
// - Once such a tracker fails it never matches again (it stops updating its position), so after
//   a failure each frame is retried with a fresh tracker started from the last matched frame and
//   box: the track resumes when the object is still near its last box.
class OpenCvTracker : public ObjectTracker::Impl {
 public:
  using Factory = std::function<cv::Ptr<cv::Tracker>()>;
  OpenCvTracker(Factory factory, const cv::Mat& bgr, const cv::Rect& box)
      : factory_(std::move(factory)),
        tracker_(factory_()),
        last_frame_(bgr.clone()),
        last_box_(box) {
    tracker_->init(bgr, box);
  }
  bool Update(const cv::Mat& bgr, cv::Rect& box) override {
    if (failed_) {
      tracker_ = factory_();
      tracker_->init(last_frame_, last_box_);
    }
    bool matched = tracker_->update(bgr, box);
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    if (matched) {
      matched = (box & frame).area() > 0 &&
                PatchCorrelation(last_frame_, last_box_, bgr, box) >= kMinMatchCorrelation;
    }
    failed_ = !matched;
    if (matched) {
      bgr.copyTo(last_frame_);
      last_box_ = box & frame;
    }
    return matched;
  }

 private:
  Factory factory_;
  cv::Ptr<cv::Tracker> tracker_;
  cv::Mat last_frame_;  // the last frame the tracker matched, and its box there
  cv::Rect last_box_;
  bool failed_ = false;
};

class CamShiftTracker : public ObjectTracker::Impl {
 public:
  CamShiftTracker(const cv::Mat& bgr, const cv::Rect& box) : window_(box) {
    cv::Mat hue, mask;
    HueAndMask(bgr, hue, mask);
    const int channels[] = {0};
    const int bins[] = {kHueBins};
    const float hue_range[] = {0, 180};
    const float* ranges[] = {hue_range};
    cv::Mat roi_hue = hue(box), roi_mask = mask(box);
    cv::calcHist(&roi_hue, 1, channels, roi_mask, histogram_, 1, bins, ranges);
    cv::normalize(histogram_, histogram_, 0, 255, cv::NORM_MINMAX);
    first_evidence_ = cv::mean(BackProject(bgr)(box))[0];
  }

  bool Update(const cv::Mat& bgr, cv::Rect& box) override {
    const cv::Mat back_projection = BackProject(bgr);
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    window_ &= frame;
    if (window_.area() == 0) return false;
    const cv::RotatedRect found =
        cv::CamShift(back_projection, window_,
                     cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1));
    box = found.boundingRect();
    const cv::Rect inside = box & frame;
    if (inside.area() == 0) return false;
    return cv::mean(back_projection(inside))[0] >= kMinCamShiftEvidence * first_evidence_;
  }

 private:
  static constexpr int kHueBins = 16;

  // Hue, and the mask of pixels with enough saturation and brightness for their hue to mean
  // something (OpenCV's camshift sample).
  static void HueAndMask(const cv::Mat& bgr, cv::Mat& hue, cv::Mat& mask) {
    cv::Mat hsv;
    cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
    cv::inRange(hsv, cv::Scalar(0, 60, 32), cv::Scalar(180, 255, 255), mask);
    cv::extractChannel(hsv, hue, 0);
  }

  cv::Mat BackProject(const cv::Mat& bgr) const {
    cv::Mat hue, mask, back_projection;
    HueAndMask(bgr, hue, mask);
    const int channels[] = {0};
    const float hue_range[] = {0, 180};
    const float* ranges[] = {hue_range};
    cv::calcBackProject(&hue, 1, channels, histogram_, back_projection, ranges);
    back_projection &= mask;
    return back_projection;
  }

  cv::Mat histogram_;
  cv::Rect window_;
  double first_evidence_ = 0;
};

}  // namespace

ObjectTracker::ObjectTracker(const cv::Mat& first_frame, const cv::Rect& box, TrackerKind kind)
    : kind_(kind) {
  if (first_frame.empty()) throw std::invalid_argument("tracking from an empty frame");
  const cv::Rect frame(0, 0, first_frame.cols, first_frame.rows);
  if (box.width < kMinBoxSide || box.height < kMinBoxSide || (box & frame) != box) {
    throw std::invalid_argument("the object's box " + std::to_string(box.x) + "," +
                                std::to_string(box.y) + "," + std::to_string(box.width) + "," +
                                std::to_string(box.height) + " must lie inside the " +
                                std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                " frame and be at least " + std::to_string(kMinBoxSide) + "x" +
                                std::to_string(kMinBoxSide) + " pixels");
  }
  const cv::Mat bgr = AsBgr(first_frame);
  switch (kind) {
    case TrackerKind::kCsrt:
      impl_ = std::make_unique<OpenCvTracker>(
          [] {
            cv::TrackerCSRT::Params params;
            params.psr_threshold = kCsrtMinPeakToSidelobe;
            // Without its colour segmentation of the object CSRT costs far less per 640x480
            // frame and follows the generated walks as well (docs/results/capture.md, "What a
            // frame costs on the device").
            params.use_segmentation = false;
            return cv::Ptr<cv::Tracker>(cv::TrackerCSRT::create(params));
          },
          bgr, box);
      break;
    case TrackerKind::kKcf:
      impl_ = std::make_unique<OpenCvTracker>(
          [] { return cv::Ptr<cv::Tracker>(cv::TrackerKCF::create()); }, bgr, box);
      break;
    case TrackerKind::kCamShift: impl_ = std::make_unique<CamShiftTracker>(bgr, box); break;
  }
}

ObjectTracker::~ObjectTracker() = default;

TrackedBox ObjectTracker::Track(const cv::Mat& frame) {
  if (frame.empty()) throw std::invalid_argument("tracking into an empty frame");
  cv::Rect box;
  const cv::Mat bgr = AsBgr(frame);
  const bool matched = impl_->Update(bgr, box);
  TrackedBox tracked;
  tracked.box = box & cv::Rect(0, 0, frame.cols, frame.rows);
  tracked.lost = !matched || box.area() == 0 ||
                 tracked.box.area() < kMinVisibleFraction * box.area() ||
                 tracked.box.width < kMinBoxSide || tracked.box.height < kMinBoxSide;
  return tracked;
}

}  // namespace orbit
