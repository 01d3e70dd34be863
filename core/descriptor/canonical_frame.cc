#include "core/descriptor/canonical_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace orbit {
namespace {

// The mean of every k x k block of `bgr` (k >= 2), rounded; rows and columns past the last
// whole block are left out (fewer than k of them). What INTER_AREA computes for an integer
// factor, as two passes of integer additions: k rows summed into one (vectorised), then k
// pixels of that sum into one. OpenCV's INTER_AREA takes several times longer on 3 channels.
cv::Mat BlockMeans(const cv::Mat& bgr, int k) {
  const int width = bgr.cols / k, height = bgr.rows / k;
  const std::size_t span = static_cast<std::size_t>(width) * k * 3;  // bytes of whole blocks
  const std::uint32_t area = static_cast<std::uint32_t>(k * k);
  cv::Mat out(height, width, CV_8UC3);
  // One row of blocks: its k rows summed into `sums`, then each block's k columns.
  const auto block_row = [&](int y, auto& sums) {
    using Sum = typename std::decay_t<decltype(sums)>::value_type;
    std::fill(sums.begin(), sums.end(), Sum{0});
    for (int dy = 0; dy < k; ++dy) {
      const std::uint8_t* in = bgr.ptr<std::uint8_t>(y * k + dy);
      for (std::size_t i = 0; i < span; ++i) sums[i] = static_cast<Sum>(sums[i] + in[i]);
    }
    std::uint8_t* row = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        std::uint32_t sum = 0;
        const std::size_t first = static_cast<std::size_t>(x) * k * 3 + c;
        for (int dx = 0; dx < k; ++dx) sum += sums[first + static_cast<std::size_t>(dx) * 3];
        row[x * 3 + c] = static_cast<std::uint8_t>((sum + area / 2) / area);
      }
    }
  };
  // 16-bit sums (twice the lanes per vector) while k rows cannot overflow them: 16 x 255.
  std::vector<std::uint16_t> narrow(k <= 16 ? span : 0);
  std::vector<std::uint32_t> wide(k > 16 ? span : 0);
  for (int y = 0; y < height; ++y) {
    if (k <= 16) {
      block_row(y, narrow);
    } else {
      block_row(y, wide);
    }
  }
  return out;
}

// Step 1: resampled to about `area` pixels, aspect ratio kept: area averaging when shrinking
// (by whole blocks first when the factor is 2 or more, then bilinear for the rest), bilinear
// when growing.
cv::Mat CanonicalSize(const cv::Mat& bgr, int area) {
  if (area <= 0) return bgr.clone();
  const double scale = std::sqrt(double(area) / (double(bgr.cols) * bgr.rows));
  const int width = std::max(1, static_cast<int>(std::lround(bgr.cols * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(bgr.rows * scale)));
  if (width == bgr.cols && height == bgr.rows) return bgr.clone();
  const int block = static_cast<int>(1 / scale);
  if (block >= 2 && bgr.cols / block >= width && bgr.rows / block >= height) {
    cv::Mat blocks = BlockMeans(bgr, block);
    if (blocks.cols == width && blocks.rows == height) return blocks;
    // Less than a factor 2 is left: bilinear is as good there and faster than INTER_AREA.
    cv::Mat resized;
    cv::resize(blocks, resized, cv::Size(width, height), 0, 0, cv::INTER_LINEAR);
    return resized;
  }
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
