#include "core/descriptor/appearance_channels.h"

#include <algorithm>
#include <array>
#include <cmath>
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
  // Per saturation and value bin, the count spread over every hue (below).
  std::array<double, kSaturationBins * kValueBins> any_hue{};
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3b* row = hsv.ptr<cv::Vec3b>(y);
    for (int x = 0; x < hsv.cols; ++x) {
      const int value = row[x][2] * kValueBins / 256;
      if (value == 0) {
        // Hue and saturation mean nothing for a dark pixel: where sensor noise would scatter
        // dark pixels over every hue and saturation, they are all counted as hue 0, saturation 0.
        counts[0] += 1;
        continue;
      }
      const int saturation = row[x][1] * kSaturationBins / 256;
      const int hue = row[x][0] * kHueBins / 180;
      // A pixel's hue is as sure as its chroma (max - min of its channels) stands above the
      // noise left after the canonical blur: below kSureChroma, the share it lacks is spread
      // over every hue, so that noise, which turns a grey's hue random, moves no bin.
      const double chroma = row[x][1] * row[x][2] / 255.0;
      const double sure = std::min(1.0, chroma / kSureChroma);
      counts[(hue * kSaturationBins + saturation) * kValueBins + value] += sure;
      any_hue[saturation * kValueBins + value] += 1 - sure;
    }
  }
  for (int h = 0; h < kHueBins; ++h) {
    for (int sv = 0; sv < kSaturationBins * kValueBins; ++sv) {
      counts[h * kSaturationBins * kValueBins + sv] += any_hue[sv] / kHueBins;
    }
  }
  return counts;
}

std::array<double, kGradientChannelSize> GradientHistogram(const cv::Mat& small) {
  cv::Mat grey, dx, dy, magnitude, angle;
  cv::cvtColor(small, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::Sobel(grey, dx, CV_32F, 1, 0, 1);  // central differences, as HOG's [-1, 0, 1]
  cv::Sobel(grey, dy, CV_32F, 0, 1, 1);
  // Vectorised; its angles are good to about 0.3 degrees, a 70th of a bin.
  cv::cartToPolar(dx, dy, magnitude, angle, /*angleInDegrees=*/true);  // angle 0..360
  std::array<double, kGradientChannelSize> histogram{};
  const int cell_side = kAppearanceSide / kGradientCellsPerSide;
  constexpr float kBinWidth = 180.0f / kGradientOrientations;
  for (int y = 0; y < kAppearanceSide; ++y) {
    const float* magnitudes = magnitude.ptr<float>(y);
    const float* angles = angle.ptr<float>(y);
    double* cell_row =
        histogram.data() + (y / cell_side) * kGradientCellsPerSide * kGradientOrientations;
    for (int x = 0; x < kAppearanceSide; ++x) {
      const float m = magnitudes[x];
      if (m == 0) continue;
      float unsigned_angle = angles[x] >= 180.0f ? angles[x] - 180.0f : angles[x];
      if (unsigned_angle >= 180.0f) unsigned_angle -= 180.0f;
      // Split between the two nearest bin centres (bin b is centred at (b + 0.5) * width).
      const float position = unsigned_angle / kBinWidth - 0.5f;
      const int lower = static_cast<int>(std::floor(position));
      const float upper_share = position - static_cast<float>(lower);
      double* bins = cell_row + (x / cell_side) * kGradientOrientations;
      bins[(lower + kGradientOrientations) % kGradientOrientations] += m * (1 - upper_share);
      bins[(lower + 1) % kGradientOrientations] += m * upper_share;
    }
  }
  // L2-Hys per cell: normalise, clip at 0.2, normalise again, each time with a floor of
  // kFlatCellShare of the mean cell's norm added to the cell's own, so that a flat cell, whose
  // gradients are the sensor's noise, stays small instead of being raised to an object cell's.
  for (int pass = 0; pass < 2; ++pass) {
    std::array<double, kGradientCellsPerSide * kGradientCellsPerSide> norms{};
    double mean_norm = 0;
    for (std::size_t cell = 0; cell < norms.size(); ++cell) {
      double sum = 0;
      for (int b = 0; b < kGradientOrientations; ++b) {
        const double bin = histogram[cell * kGradientOrientations + b];
        sum += bin * bin;
      }
      norms[cell] = std::sqrt(sum);
      mean_norm += norms[cell] / norms.size();
    }
    const double floor = kFlatCellShare * mean_norm + 1e-3;
    for (std::size_t cell = 0; cell < norms.size(); ++cell) {
      double* bins = histogram.data() + cell * kGradientOrientations;
      const double scale = 1.0 / (norms[cell] + floor);
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
  // Bilinear, shrinking too: the canonical frame is already blurred (a deviation of 2 of its
  // pixels, docs/design.md#canonical-frame), so area averaging, several times slower on a
  // factor that is not whole, would add little.
  cv::Mat small;
  cv::resize(canonical, small, cv::Size(kAppearanceSide, kAppearanceSide), 0, 0, cv::INTER_LINEAR);
  const auto colour = ColourHistogram(small);
  const auto gradient = GradientHistogram(small);
  ScaleChannel(colour, kColourNorm,
               std::span<std::uint8_t>(values.data() + kColourChannelOffset, kColourChannelSize));
  ScaleChannel(
      gradient, kGradientNorm,
      std::span<std::uint8_t>(values.data() + kGradientChannelOffset, kGradientChannelSize));
}

}  // namespace orbit
