#include "core/canonical_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace orbit {
namespace {

// Step 1: resampled to about `area` pixels, aspect ratio kept.
cv::Mat CanonicalSize(const cv::Mat& bgr, int area) {
  if (area <= 0) return bgr.clone();
  const double scale = std::sqrt(double(area) / (double(bgr.cols) * bgr.rows));
  const int width = std::max(1, static_cast<int>(std::lround(bgr.cols * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(bgr.rows * scale)));
  if (width == bgr.cols && height == bgr.rows) return bgr.clone();
  cv::Mat resized;
  cv::resize(bgr, resized, cv::Size(width, height), 0, 0,
             scale < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
  return resized;
}

// Step 3, in place.
void NormaliseBrightness(cv::Mat& bgr) {
  std::array<int, 256> histogram{};  // of the brightest channel, over pixels above kDarkLevel
  int bright = 0;
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint8_t* p = bgr.ptr<std::uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x, p += 3) {
      const int value = std::max({p[0], p[1], p[2]});
      if (value > kDarkLevel) {
        ++histogram[value];
        ++bright;
      }
    }
  }
  if (bright == 0 || bright * 100 < bgr.rows * bgr.cols) return;
  // The smallest value v with at least kBrightnessPercentile of the bright pixels at or below v.
  const double wanted = kBrightnessPercentile * bright;
  int below = 0, percentile = kDarkLevel + 1;
  for (int v = kDarkLevel + 1; v < 256; ++v) {
    below += histogram[v];
    if (below >= wanted) {
      percentile = v;
      break;
    }
  }
  bgr.convertTo(bgr, CV_8UC3, double(kBrightnessTarget) / percentile);
}

}  // namespace

cv::Mat CanonicalFrame(const cv::Mat& bgr, const CanonicalFrameOptions& options) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw std::invalid_argument("CanonicalFrame needs a non-empty 8-bit BGR image, got type " +
                                std::to_string(bgr.type()) + " of " + std::to_string(bgr.cols) +
                                "x" + std::to_string(bgr.rows));
  }
  cv::Mat frame = CanonicalSize(bgr, options.area);
  if (options.blur_sigma > 0) cv::GaussianBlur(frame, frame, cv::Size(0, 0), options.blur_sigma);
  if (options.normalise_brightness) NormaliseBrightness(frame);
  return frame;
}

}  // namespace orbit
