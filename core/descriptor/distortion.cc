#include "core/descriptor/distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/base/seeded_random.h"

namespace orbit {
namespace {

constexpr double kMatlabEps = std::numeric_limits<double>::epsilon();  // MATLAB's eps

void RequireEightBitImage(const cv::Mat& image, const char* function) {
  if (image.empty() || image.depth() != CV_8U || image.channels() > 4) {
    throw std::invalid_argument(std::string(function) +
                                ": need a non-empty 8-bit image with 1 to 4 channels");
  }
}

// MATLAB's sign().
int Sign(double x) { return (x > 0) - (x < 0); }

// MATLAB's colon operator `0:step:last` for integer step (+1 or -1) and integer last.
std::vector<double> Colon(int step, int last) {
  std::vector<double> values;
  if (step == 0) return values;  // 0:0:last is empty in MATLAB
  for (int v = 0; step > 0 ? v <= last : v >= last; v += step) values.push_back(v);
  return values;
}

}  // namespace

cv::Mat MotionBlurKernel(double length, double angle_degrees) {
  if (!std::isfinite(length) || !std::isfinite(angle_degrees)) {
    throw std::invalid_argument("MotionBlurKernel: length and angle must be finite");
  }
  // fspecial.m, case 'motion', line by line.
  const double len = std::max(1.0, length);
  const double half = (len - 1) / 2;  // rotate half length around center
  const double phi = (angle_degrees - 180.0 * std::floor(angle_degrees / 180.0)) / 180.0 *
                     std::numbers::pi;  // mod(p3,180)/180*pi
  const double cosphi = std::cos(phi);
  const double sinphi = std::sin(phi);
  const int xsign = Sign(cosphi);
  const double linewdt = 1;

  // Mesh for the half matrix; the eps terms give the right size at 0 and 90 degrees.
  const int sx = static_cast<int>(std::trunc(half * cosphi + linewdt * xsign - len * kMatlabEps));
  const int sy = static_cast<int>(std::trunc(half * sinphi + linewdt - len * kMatlabEps));
  std::vector<double> xs = Colon(xsign, sx);
  const std::vector<double> ys = Colon(1, sy);
  if (xs.empty()) xs.push_back(0);  // unreachable: cos(phi) never vanishes for phi in [0, pi)
  const int rows = static_cast<int>(ys.size());
  const int cols = static_cast<int>(xs.size());

  cv::Mat dist(rows, cols, CV_64F);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double x = xs[c], y = ys[r];
      // Shortest distance from the pixel to the rotated line.
      double d = y * cosphi - x * sinphi;
      const double rad = std::sqrt(x * x + y * y);
      // Beyond the line's end point but within the line width: distance to the end point.
      if (rad >= half && std::abs(d) <= linewdt) {
        const double x2lastpix = half - std::abs((x + d * sinphi) / cosphi);
        d = std::sqrt(d * d + x2lastpix * x2lastpix);
      }
      d = linewdt + kMatlabEps - std::abs(d);
      dist.at<double>(r, c) = d < 0 ? 0 : d;  // zero beyond the line width
    }
  }

  // Unfold the half matrix: rot90(dist, 2) in the top-left corner, dist in the bottom-right,
  // sharing the centre element.
  cv::Mat kernel = cv::Mat::zeros(2 * rows - 1, 2 * cols - 1, CV_64F);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      kernel.at<double>(r, c) = dist.at<double>(rows - 1 - r, cols - 1 - c);
    }
  }
  dist.copyTo(kernel(cv::Rect(cols - 1, rows - 1, cols, rows)));
  kernel /= cv::sum(kernel)[0] + kMatlabEps * len * len;
  if (cosphi > 0) cv::flip(kernel, kernel, 0);  // flipud
  return kernel;
}

cv::Mat MotionBlur(const cv::Mat& image, double length, double angle_degrees) {
  RequireEightBitImage(image, "MotionBlur");
  const cv::Mat kernel = MotionBlurKernel(length, angle_degrees);
  // Only the kernel's non-zero taps matter (about 40 of 105 for the protocol's kernel).
  struct Tap {
    int dy, dx;
    double weight;
  };
  std::vector<Tap> taps;
  const int anchor_y = kernel.rows / 2, anchor_x = kernel.cols / 2;
  for (int r = 0; r < kernel.rows; ++r) {
    for (int c = 0; c < kernel.cols; ++c) {
      const double w = kernel.at<double>(r, c);
      if (w != 0) taps.push_back({r - anchor_y, c - anchor_x, w});
    }
  }
  // Row by row, tap by tap: each value's sum still adds its taps in the kernel's order (a tap
  // beyond the image adds nothing), so the sums are those of the pixel-by-pixel correlation
  // to the last bit, while the inner loop runs over a whole row without a bounds check.
  const int channels = image.channels();
  const int row_values = image.cols * channels;
  std::vector<double> sums(static_cast<std::size_t>(row_values));
  cv::Mat result(image.size(), image.type());
  for (int y = 0; y < image.rows; ++y) {
    std::fill(sums.begin(), sums.end(), 0.0);
    for (const Tap& tap : taps) {
      const int yy = y + tap.dy;
      if (yy < 0 || yy >= image.rows) continue;  // zero pad
      const std::uint8_t* in = image.ptr<std::uint8_t>(yy);
      const int shift = tap.dx * channels;
      const int begin = std::max(0, -tap.dx) * channels;
      const int end = std::min(image.cols, image.cols - tap.dx) * channels;
      const double weight = tap.weight;
      for (int i = begin; i < end; ++i) sums[i] += weight * in[i + shift];
    }
    std::uint8_t* out = result.ptr<std::uint8_t>(y);
    for (int i = 0; i < row_values; ++i) {
      out[i] = cv::saturate_cast<std::uint8_t>(std::round(sums[i]));
    }
  }
  return result;
}

cv::Mat AddGaussianNoise(const cv::Mat& image, double variance, std::uint64_t seed) {
  RequireEightBitImage(image, "AddGaussianNoise");
  if (!std::isfinite(variance) || variance < 0) {
    throw std::invalid_argument("AddGaussianNoise: variance must be finite and >= 0");
  }
  SeededRandom random(seed);
  const double sigma = std::sqrt(variance);
  cv::Mat result(image.size(), image.type());
  const int values_per_row = image.cols * image.channels();
  for (int y = 0; y < image.rows; ++y) {
    const std::uint8_t* in = image.ptr<std::uint8_t>(y);
    std::uint8_t* out = result.ptr<std::uint8_t>(y);
    for (int i = 0; i < values_per_row; ++i) {
      const double noisy = std::clamp(in[i] / 255.0 + sigma * random.Normal(), 0.0, 1.0);
      out[i] = static_cast<std::uint8_t>(std::round(noisy * 255.0));
    }
  }
  return result;
}

}  // namespace orbit
