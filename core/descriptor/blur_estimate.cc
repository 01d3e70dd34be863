#include "core/descriptor/blur_estimate.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace orbit {
namespace {

// The blur along one axis (dx, dy: the neighbour's offset, (0, 1) or (1, 0)), as in the header.
double AxisBlur(const cv::Mat& grey, const cv::Mat& reblurred, int dx, int dy) {
  const cv::Rect here(dx, dy, grey.cols - dx, grey.rows - dy);
  const cv::Rect before(0, 0, grey.cols - dx, grey.rows - dy);
  cv::Mat frame_variation, blurred_variation, lost;
  cv::absdiff(grey(here), grey(before), frame_variation);
  cv::absdiff(reblurred(here), reblurred(before), blurred_variation);
  cv::subtract(frame_variation, blurred_variation, lost);  // saturates at 0: max(0, D_F - D_B)
  const double total = cv::sum(frame_variation)[0];
  if (total <= 0) return 0;
  return (total - cv::sum(lost)[0]) / total;
}

}  // namespace

double EstimateBlur(const cv::Mat& image) {
  if (image.empty() || image.depth() != CV_8U || image.channels() == 2 || image.channels() > 4) {
    throw std::invalid_argument(
        "EstimateBlur needs a non-empty 8-bit image of 1, 3 or 4 "
        "channels, got type " +
        std::to_string(image.type()));
  }
  if (image.cols < 2 || image.rows < 2) return 0;
  cv::Mat grey;
  if (image.channels() == 1) {
    grey = image;
  } else {
    cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  }
  cv::Mat vertical, horizontal;
  cv::blur(grey, vertical, cv::Size(1, kBlurEstimateKernel));
  cv::blur(grey, horizontal, cv::Size(kBlurEstimateKernel, 1));
  return std::max(AxisBlur(grey, vertical, 0, 1), AxisBlur(grey, horizontal, 1, 0));
}

}  // namespace orbit
