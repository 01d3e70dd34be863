#include "client/object_tracker.h"

#include <algorithm>
#include <cmath>
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
    case TrackerKind::kTemplate: return "template";
  }
  return "?";
}

std::string_view TrackerSummary(TrackerKind kind) {
  switch (kind) {
    case TrackerKind::kTemplate:
      return "the default: template matching on a reduced frame, cheap enough for a phone";
    case TrackerKind::kCsrt:
      return "correlation filter: holds on longer in clutter, at many times the cost";
    case TrackerKind::kKcf: return "kernelised correlation filter: costly on large boxes";
    case TrackerKind::kCamShift: return "mean shift on the object's hues: drifts in clutter";
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

// Template matching on a reduced frame (docs/design.md#object-tracking): the object's last
// appearance, reduced so that its box's longer side is kTemplateSide pixels, is searched for in a
// window around its last box reduced alike. The match moves the box, which keeps the first
// frame's size (a scale search let the box creep onto background on the generated walks, whose
// boxes change with the object's outline as it turns more than with its distance); the template
// then takes in part of the new appearance, so that it follows the object as it turns. The cost
// follows the template's size, not the frame's.
class TemplateTracker : public ObjectTracker::Impl {
 public:
  TemplateTracker(const cv::Mat& bgr, const cv::Rect& box)
      : centre_(box.x + box.width / 2.0, box.y + box.height / 2.0), size_(box.size()) {
    const double reduction = Reduction();
    template_size_ = cv::Size(std::max(4, static_cast<int>(std::lround(size_.width * reduction))),
                              std::max(4, static_cast<int>(std::lround(size_.height * reduction))));
    cv::Mat seen;
    cv::resize(bgr(box), seen, template_size_, 0, 0, cv::INTER_AREA);
    template_ = Grey(seen);
    colours_ = Colours(seen);
  }

  bool Update(const cv::Mat& bgr, cv::Rect& box) override {
    const double reduction = Reduction();
    // The window, in frame pixels, and the same window reduced, padded where it leaves the frame.
    const cv::Size2d window_size(size_.width * (1 + 2 * kSearchMargin),
                                 size_.height * (1 + 2 * kSearchMargin));
    const cv::Point2d window_origin(centre_.x - window_size.width / 2,
                                    centre_.y - window_size.height / 2);
    const cv::Mat window = Grey(ReducedWindow(bgr, window_origin, window_size, reduction));
    if (template_size_.width > window.cols || template_size_.height > window.rows) return false;
    cv::Mat score;
    cv::matchTemplate(window, template_, score, cv::TM_CCOEFF_NORMED);
    double peak;
    cv::Point at;
    cv::minMaxLoc(score, nullptr, &peak, nullptr, &at);
    const cv::Point2d found(at.x + Subpixel(score, at, true) + template_size_.width / 2.0,
                            at.y + Subpixel(score, at, false) + template_size_.height / 2.0);
    const cv::Point2d centre = window_origin + found * (1 / reduction);
    box = BoxAt(centre, size_);
    if (peak < kMinTemplateMatch) return false;
    // The region found, at the template's size: its colours must still be the object's.
    cv::Mat seen = ReducedWindow(bgr, centre - cv::Point2d(size_.width / 2, size_.height / 2),
                                 size_, reduction);
    if (seen.size() != template_size_) {
      cv::resize(seen, seen, template_size_, 0, 0, cv::INTER_LINEAR);
    }
    const cv::Mat colours = Colours(seen);
    const double colour_distance = cv::compareHist(colours_, colours, cv::HISTCMP_BHATTACHARYYA);
    if (colour_distance > kMaxColourDistance) return false;
    centre_ = centre;
    // Take in the new appearance.
    cv::addWeighted(template_, 1 - kTemplateUpdate, Grey(seen), kTemplateUpdate, 0, template_);
    cv::addWeighted(colours_, 1 - kTemplateUpdate, colours, kTemplateUpdate, 0, colours_);
    return true;
  }

 private:
  static constexpr double kTemplateSide = 32;   // the template's longer side, reduced pixels
  static constexpr double kSearchMargin = 0.5;  // of the box's size, on each side
  // A match counts when the normalised grey correlation of template and region is at least
  // this, and the Bhattacharyya distance of their colour histograms at most kMaxColourDistance.
  // Texture alone does not tell a cluttered scene without the object from the object: the
  // best of the window's positions often correlates as well as a turning object does.
  static constexpr double kMinTemplateMatch = 0.5;
  static constexpr double kMaxColourDistance = 0.5;
  static constexpr double kTemplateUpdate = 0.3;  // share of the new appearance taken in a frame
  static constexpr int kColourLevels = 4;         // per channel, for the colour histogram

  double Reduction() const { return kTemplateSide / std::max(size_.width, size_.height); }

  static cv::Rect BoxAt(cv::Point2d centre, cv::Size2d size) {
    return cv::Rect(static_cast<int>(std::lround(centre.x - size.width / 2)),
                    static_cast<int>(std::lround(centre.y - size.height / 2)),
                    static_cast<int>(std::lround(size.width)),
                    static_cast<int>(std::lround(size.height)));
  }

  // Offset in [-0.5, 0.5] of the peak at `at` along x or y, from a parabola through it and its
  // two neighbours.
  static double Subpixel(const cv::Mat& score, cv::Point at, bool along_x) {
    const cv::Point step = along_x ? cv::Point(1, 0) : cv::Point(0, 1);
    const cv::Point before = at - step, after = at + step;
    if (before.x < 0 || before.y < 0 || after.x >= score.cols || after.y >= score.rows) return 0;
    const double l = score.at<float>(before), c = score.at<float>(at), r = score.at<float>(after);
    const double curvature = l - 2 * c + r;
    return curvature < 0 ? std::clamp(0.5 * (l - r) / curvature, -0.5, 0.5) : 0;
  }

  static cv::Mat Grey(const cv::Mat& bgr) {
    cv::Mat grey, out;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    grey.convertTo(out, CV_32F);
    return out;
  }

  // The normalised kColourLevels^3 histogram of a reduced BGR region.
  static cv::Mat Colours(const cv::Mat& bgr) {
    const int channels[] = {0, 1, 2};
    const int levels[] = {kColourLevels, kColourLevels, kColourLevels};
    const float range[] = {0, 256};
    const float* ranges[] = {range, range, range};
    cv::Mat histogram;
    cv::calcHist(&bgr, 1, channels, cv::Mat(), histogram, 3, levels, ranges);
    return histogram / std::max(1.0, cv::sum(histogram)[0]);
  }

  // The frame rectangle at `origin` of `size` (frame pixels), reduced by `reduction` (8-bit
  // BGR); the part outside the frame repeats the nearest pixels inside it.
  static cv::Mat ReducedWindow(const cv::Mat& bgr, cv::Point2d origin, cv::Size2d size,
                               double reduction) {
    const cv::Rect wanted = BoxAt(origin + cv::Point2d(size.width / 2, size.height / 2), size);
    const cv::Size out_size(std::max(1, static_cast<int>(std::lround(wanted.width * reduction))),
                            std::max(1, static_cast<int>(std::lround(wanted.height * reduction))));
    const cv::Rect inside = wanted & cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (inside.area() == 0) return cv::Mat(out_size, CV_8UC3, cv::Scalar::all(0));
    const cv::Size inside_size(
        std::max(1, static_cast<int>(std::lround(inside.width * reduction))),
        std::max(1, static_cast<int>(std::lround(inside.height * reduction))));
    cv::Mat small, out;
    cv::resize(bgr(inside), small, inside_size, 0, 0, cv::INTER_AREA);
    const int left = std::max(0, static_cast<int>(std::lround((inside.x - wanted.x) * reduction)));
    const int top = std::max(0, static_cast<int>(std::lround((inside.y - wanted.y) * reduction)));
    const int right = std::max(0, out_size.width - left - inside_size.width);
    const int bottom = std::max(0, out_size.height - top - inside_size.height);
    cv::copyMakeBorder(small, out, top, bottom, left, right, cv::BORDER_REPLICATE);
    return out;
  }

  cv::Point2d centre_;     // the object's box in the last matched frame, in frame pixels
  const cv::Size2d size_;  // the first frame's box
  cv::Size template_size_;
  cv::Mat template_;  // CV_32F grey, template_size_: the object's appearance
  cv::Mat colours_;   // Colours() of the object's appearance
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
    case TrackerKind::kTemplate: impl_ = std::make_unique<TemplateTracker>(bgr, box); break;
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
