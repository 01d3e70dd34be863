#include "core/descriptor/appearance_channels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace orbit {
namespace {

// Square roots of `counts`, scaled to Euclidean norm `norm`, rounded and clipped to 0..7, into
// `out`. All zeros stay zeros.
void ScaleChannel(std::span<const double> counts, double norm, std::span<std::uint8_t> out) {
  double energy = 0;
  for (const double count : counts) energy += count;  // sum of (sqrt count)^2
  if (energy <= 0) {
    std::fill(out.begin(), out.end(), 0);
    return;
  }
  const double scale = norm / std::sqrt(energy);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double value = std::round(std::sqrt(counts[i]) * scale);
    out[i] = static_cast<std::uint8_t>(std::min<double>(value, kDescriptorMaxValue));
  }
}

std::array<double, kColourChannelSize> ColourHistogram(const cv::Mat& small) {
  cv::Mat hsv;
  cv::cvtColor(small, hsv, cv::COLOR_BGR2HSV);  // hue 0..179, saturation and value 0..255
  std::array<double, kColourChannelSize> counts{};
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3b* row = hsv.ptr<cv::Vec3b>(y);
    for (int x = 0; x < hsv.cols; ++x) {
      const int value = row[x][2] * kValueBins / 256;
      // Hue and saturation mean nothing for a dark pixel: where sensor noise would scatter
      // dark pixels over every hue and saturation, they are all counted as hue 0, saturation 0.
      const int saturation = value == 0 ? 0 : row[x][1] * kSaturationBins / 256;
      const int hue = value == 0 ? 0 : row[x][0] * kHueBins / 180;
      counts[(hue * kSaturationBins + saturation) * kValueBins + value] += 1;
    }
  }
  return counts;
}

std::array<double, kGradientChannelSize> GradientHistogram(const cv::Mat& small) {
  cv::Mat grey, dx, dy;
  cv::cvtColor(small, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::Sobel(grey, dx, CV_32F, 1, 0, 1);  // central differences, as HOG's [-1, 0, 1]
  cv::Sobel(grey, dy, CV_32F, 0, 1, 1);
  std::array<double, kGradientChannelSize> histogram{};
  const int cell_side = kAppearanceSide / kGradientCellsPerSide;
  constexpr double kBinWidth = 180.0 / kGradientOrientations;
  for (int y = 0; y < kAppearanceSide; ++y) {
    for (int x = 0; x < kAppearanceSide; ++x) {
      const double gx = dx.at<float>(y, x), gy = dy.at<float>(y, x);
      const double magnitude = std::hypot(gx, gy);
      if (magnitude == 0) continue;
      double angle = std::atan2(gy, gx) * 180.0 / std::numbers::pi;  // -180..180
      if (angle < 0) angle += 180.0;
      if (angle >= 180.0) angle -= 180.0;
      // Split between the two nearest bin centres (bin b is centred at (b + 0.5) * width).
      const double position = angle / kBinWidth - 0.5;
      const int lower = static_cast<int>(std::floor(position));
      const double upper_share = position - lower;
      const int cell = (y / cell_side) * kGradientCellsPerSide + x / cell_side;
      double* bins = histogram.data() + cell * kGradientOrientations;
      bins[(lower + kGradientOrientations) % kGradientOrientations] +=
          magnitude * (1 - upper_share);
      bins[(lower + 1) % kGradientOrientations] += magnitude * upper_share;
    }
  }
  // L2-Hys per cell: normalise, clip at 0.2, normalise again.
  for (int cell = 0; cell < kGradientCellsPerSide * kGradientCellsPerSide; ++cell) {
    double* bins = histogram.data() + cell * kGradientOrientations;
    for (int pass = 0; pass < 2; ++pass) {
      double sum = 0;
      for (int b = 0; b < kGradientOrientations; ++b) sum += bins[b] * bins[b];
      const double scale = 1.0 / (std::sqrt(sum) + 1e-3);
      for (int b = 0; b < kGradientOrientations; ++b) {
        bins[b] = pass == 0 ? std::min(bins[b] * scale, 0.2) : bins[b] * scale;
      }
    }
  }
  return histogram;
}

}  // namespace

void AddAppearanceChannels(const cv::Mat& canonical, DescriptorValues& values) {
  if (canonical.empty() || canonical.type() != CV_8UC3) {
    throw std::invalid_argument("appearance channels need a non-empty 8-bit BGR image");
  }
  cv::Mat small;
  const bool shrinking = canonical.cols >= kAppearanceSide && canonical.rows >= kAppearanceSide;
  cv::resize(canonical, small, cv::Size(kAppearanceSide, kAppearanceSide), 0, 0,
             shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  const auto colour = ColourHistogram(small);
  const auto gradient = GradientHistogram(small);
  ScaleChannel(colour, kColourNorm,
               std::span<std::uint8_t>(values.data() + kColourChannelOffset, kColourChannelSize));
  ScaleChannel(
      gradient, kGradientNorm,
      std::span<std::uint8_t>(values.data() + kGradientChannelOffset, kGradientChannelSize));
}

}  // namespace orbit
