#include "core/descriptor/noise_estimate.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/base/cpu_dispatch.h"

namespace orbit {
namespace {

// second[i] = row[i - step] - 2 row[i] + row[i + step] for i in [step, n - step): the horizontal
// second difference of a row of interleaved channels (step = channels). A hot loop
// (core/base/cpu_dispatch.h).
ORBIT_HOT_LOOP void SecondDifference(const std::uint8_t* __restrict row, int step,
                                     std::int16_t* __restrict second, int n) {
  for (int i = step; i < n - step; ++i) {
    second[i] = static_cast<std::int16_t>(row[i - step] - 2 * row[i] + row[i + step]);
  }
}

// Sum over i in [step, n - step) of |above[i] - 2 middle[i] + below[i]|: the mask N, being
// the product of two second differences, is the vertical second difference of the horizontal
// ones.
ORBIT_HOT_LOOP std::int64_t AbsoluteResponse(const std::int16_t* __restrict above,
                                             const std::int16_t* __restrict middle,
                                             const std::int16_t* __restrict below, int step,
                                             int n) {
  std::int32_t sum = 0;  // at most 16 x 255 per value: rows of up to 500 000 values fit
  for (int i = step; i < n - step; ++i) {
    const int v = above[i] - 2 * middle[i] + below[i];
    sum += v < 0 ? -v : v;
  }
  return sum;
}

}  // namespace

double EstimateNoiseSigma(const cv::Mat& image) {
  if (image.empty() || image.depth() != CV_8U || image.channels() > 4) {
    throw std::invalid_argument("EstimateNoiseSigma: the image must be 8-bit with 1-4 channels");
  }
  if (image.rows < 3 || image.cols < 3) return 0;
  cv::Mat pixels = image;
  if (image.channels() == 4) cv::cvtColor(image, pixels, cv::COLOR_BGRA2BGR);  // alpha ignored
  if (pixels.channels() == 2) {
    throw std::invalid_argument("EstimateNoiseSigma: the image must have 1, 3 or 4 channels");
  }
  const int step = pixels.channels();
  const int n = pixels.cols * step;
  // Horizontal second differences of three consecutive rows, rotated as the rows go down.
  std::vector<std::int16_t> rows[3] = {std::vector<std::int16_t>(n), std::vector<std::int16_t>(n),
                                       std::vector<std::int16_t>(n)};
  for (int r = 0; r < 2; ++r)
    RunHotLoop<SecondDifference>(pixels.ptr<std::uint8_t>(r), step, rows[r].data(), n);
  std::int64_t sum = 0;
  for (int r = 1; r + 1 < pixels.rows; ++r) {
    std::vector<std::int16_t>& below = rows[(r + 1) % 3];
    RunHotLoop<SecondDifference>(pixels.ptr<std::uint8_t>(r + 1), step, below.data(), n);
    sum += RunHotLoop<AbsoluteResponse>(rows[(r - 1) % 3].data(), rows[r % 3].data(), below.data(),
                                        step, n);
  }
  const double values = static_cast<double>(pixels.rows - 2) * (pixels.cols - 2) * step;
  return std::sqrt(std::numbers::pi / 2) * static_cast<double>(sum) / (6 * values);
}

}  // namespace orbit
