#include "core/descriptor/appearance_channels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace orbit {
namespace {

constexpr int kDarkBin = 0;  // hue 0, saturation 0, value 0: every dark pixel's bin

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

using ColourCounts = std::array<double, kColourChannelSize>;

// The colour histogram of a 64x64 frame, of its border ring alone, and each pixel's own bin.
struct ColourPixels {
  ColourCounts whole{};
  ColourCounts border{};
  std::array<std::uint8_t, kAppearanceSide * kAppearanceSide> bin{};
};

// A pixel's hue is as sure as its chroma (max - min of its channels) stands above the noise left
// after the canonical blur: from kSureChroma on it counts in full.
double HueCertainty(const cv::Vec3b& hsv) {
  const double chroma = hsv[1] * hsv[2] / 255.0;
  return std::min(1.0, chroma / kSureChroma);
}

// Adds to `counts` what a pixel's share `sure` of its hue and the share spread over every hue,
// `any_hue` per saturation and value bin, make.
void SpreadOverHues(const std::array<double, kSaturationBins * kValueBins>& any_hue,
                    ColourCounts& counts) {
  for (int h = 0; h < kHueBins; ++h) {
    for (int sv = 0; sv < kSaturationBins * kValueBins; ++sv) {
      counts[h * kSaturationBins * kValueBins + sv] += any_hue[sv] / kHueBins;
    }
  }
}

// A hue's neighbouring bin across the nearer edge of its own (circularly) and the share of its
// count that bin takes: 1/2 at the edge, falling linearly to 0 at `reach` bin widths from it
// (docs/design.md#soft-hue-edges). `reach` 0: hard edges, the share is always 0.
struct HueEdgeShare {
  int neighbour;
  double share;
};
HueEdgeShare ShareAcrossHueEdge(int hue, double reach) {
  if (reach <= 0) return {0, 0.0};  // hard edges: nothing crosses, whichever the neighbour
  const double position = hue * static_cast<double>(kHueBins) / 180.0;  // in bin widths
  const int own = hue * kHueBins / 180;
  const double from_lower = position - own;  // 0..1 within the own bin
  const bool lower_edge = from_lower < 0.5;
  const double distance = lower_edge ? from_lower : 1 - from_lower;
  const int neighbour = (own + (lower_edge ? kHueBins - 1 : 1)) % kHueBins;
  if (distance >= reach) return {neighbour, 0.0};
  return {neighbour, 0.5 * (1 - distance / reach)};
}

// `hsv`: the 64x64 frame in OpenCV's 8-bit HSV (hue 0..179, saturation and value 0..255);
// `hue_edge_reach`: ShareAcrossHueEdge's reach.
ColourPixels ColourHistogram(const cv::Mat& hsv, double hue_edge_reach) {
  ColourPixels pixels;
  // Per saturation and value bin, the count spread over every hue (below).
  std::array<double, kSaturationBins * kValueBins> any_hue{}, border_any_hue{};
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3b* row = hsv.ptr<cv::Vec3b>(y);
    const bool border_row = y < kBorderRing || y >= hsv.rows - kBorderRing;
    for (int x = 0; x < hsv.cols; ++x) {
      const bool border = border_row || x < kBorderRing || x >= hsv.cols - kBorderRing;
      const int value = row[x][2] * kValueBins / 256;
      if (value == 0) {
        // Hue and saturation mean nothing for a dark pixel: where sensor noise would scatter
        // dark pixels over every hue and saturation, they are all counted as hue 0, saturation 0.
        pixels.whole[kDarkBin] += 1;
        if (border) pixels.border[kDarkBin] += 1;
        pixels.bin[y * kAppearanceSide + x] = kDarkBin;
        continue;
      }
      const int saturation = row[x][1] * kSaturationBins / 256;
      const int hue = row[x][0] * kHueBins / 180;
      // A pixel's hue is as sure as its chroma (max - min of its channels) stands above the
      // noise left after the canonical blur: below kSureChroma, the share it lacks is spread
      // over every hue, so that noise, which turns a grey's hue random, moves no bin.
      const double sure = HueCertainty(row[x]);
      const int bin = (hue * kSaturationBins + saturation) * kValueBins + value;
      pixels.bin[y * kAppearanceSide + x] = static_cast<std::uint8_t>(bin);
      const HueEdgeShare across = ShareAcrossHueEdge(row[x][0], hue_edge_reach);
      const int neighbour_bin =
          (across.neighbour * kSaturationBins + saturation) * kValueBins + value;
      const double own_count = sure * (1 - across.share);
      const double neighbour_count = sure * across.share;
      pixels.whole[bin] += own_count;
      pixels.whole[neighbour_bin] += neighbour_count;
      any_hue[saturation * kValueBins + value] += 1 - sure;
      if (border) {
        pixels.border[bin] += own_count;
        pixels.border[neighbour_bin] += neighbour_count;
        border_any_hue[saturation * kValueBins + value] += 1 - sure;
      }
    }
  }
  SpreadOverHues(any_hue, pixels.whole);
  SpreadOverHues(border_any_hue, pixels.border);
  return pixels;
}

// Per colour bin, the share of the frame's count that is the object's
// (docs/design.md#foreground-estimate): the border ring is background, and the background's share
// of the frame is the least, over the ring's common colours, of how much of the frame that colour
// covers against how much of the ring; each bin keeps what the background does not account for,
// so a colour the object shares with the background is removed only as far as the background
// covers it. Dark pixels, which carry no colour to tell the two apart, are kept. Something is
// always left: with the background's share at most kMaxBackgroundShare, the expected counts sum
// to at most that share of the frame's.
ColourCounts ForegroundShares(const ColourPixels& pixels) {
  // Every pixel counts 1 in all (its own bin's share and the share spread over every hue).
  constexpr int kInner = kAppearanceSide - 2 * kBorderRing;
  constexpr double kFramePixels = kAppearanceSide * kAppearanceSide;
  constexpr double kRingPixels = kFramePixels - kInner * kInner;
  double background = kMaxBackgroundShare;
  for (int b = kDarkBin + 1; b < kColourChannelSize; ++b) {
    const double ring = pixels.border[b] / kRingPixels;
    if (ring < kCommonBorderColour) continue;
    background = std::min(background, pixels.whole[b] / kFramePixels / ring);
  }
  ColourCounts shares;
  shares.fill(1.0);
  for (int b = kDarkBin + 1; b < kColourChannelSize; ++b) {
    if (pixels.whole[b] <= 0) continue;
    const double expected = background * kFramePixels * pixels.border[b] / kRingPixels;
    shares[b] = std::max(0.0, pixels.whole[b] - expected) / pixels.whole[b];
  }
  return shares;
}

std::array<double, kGradientChannelSize> GradientHistogram(const cv::Mat& small,
                                                           const ColourPixels& pixels,
                                                           const ColourCounts& foreground) {
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
      // The background's gradients count as little as its colour does.
      const float m =
          magnitudes[x] * static_cast<float>(foreground[pixels.bin[y * kAppearanceSide + x]]);
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

// The colour layout: per half of the frame (upper first), the hue-saturation-value histogram of
// its pixels with kLayoutSaturationBins saturations, each pixel counted as ColourHistogram counts
// it (the unsure part of a hue spread over every hue) and weighed by the object's share of its
// colour-histogram bin. Dark pixels are left out (docs/design.md#colour-layout): how many of them
// each half holds follows the box (a dark ground above and below the object, shadows) more than
// the object.
ColourCounts ColourLayout(const cv::Mat& hsv, const ColourPixels& pixels,
                          const ColourCounts& foreground) {
  ColourCounts layout{};
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3b* row = hsv.ptr<cv::Vec3b>(y);
    double* band = layout.data() + (y * kLayoutBands / hsv.rows) * kLayoutBandSize;
    for (int x = 0; x < hsv.cols; ++x) {
      const int value = row[x][2] * kValueBins / 256;
      if (value == 0) continue;
      const double object = foreground[pixels.bin[y * kAppearanceSide + x]];
      const int saturation = row[x][1] * kLayoutSaturationBins / 256;
      const int hue = row[x][0] * kHueBins / 180;
      const double sure = HueCertainty(row[x]);
      const int sv = saturation * kValueBins + value;
      band[hue * kLayoutSaturationBins * kValueBins + sv] += object * sure;
      if (sure < 1) {
        for (int h = 0; h < kHueBins; ++h) {
          band[h * kLayoutSaturationBins * kValueBins + sv] += object * (1 - sure) / kHueBins;
        }
      }
    }
  }
  return layout;
}

}  // namespace

void AddAppearanceChannels(const cv::Mat& canonical, DescriptorVariant variant,
                           DescriptorValues& values) {
  if (canonical.empty() || canonical.type() != CV_8UC3) {
    throw std::invalid_argument("appearance channels need a non-empty 8-bit BGR image");
  }
  if (!HasAppearanceChannels(variant)) {
    throw std::invalid_argument(std::string(VariantName(variant)) + " has no appearance channels");
  }
  // Bilinear, shrinking too: the canonical frame is already blurred (a deviation of 2 of its
  // pixels, docs/design.md#canonical-frame), so area averaging, several times slower on a
  // factor that is not whole, would add little.
  cv::Mat small;
  cv::resize(canonical, small, cv::Size(kAppearanceSide, kAppearanceSide), 0, 0, cv::INTER_LINEAR);
  cv::Mat hsv;
  cv::cvtColor(small, hsv, cv::COLOR_BGR2HSV);
  const bool soft = variant == DescriptorVariant::kCeddSoftHsvHog;
  const ColourPixels pixels = ColourHistogram(hsv, soft ? kHueEdgeReach : 0.0);
  const ColourCounts foreground = ForegroundShares(pixels);
  ColourCounts colour;
  if (variant != DescriptorVariant::kCeddHsvLayout) {
    for (int b = 0; b < kColourChannelSize; ++b) colour[b] = pixels.whole[b] * foreground[b];
  } else {
    colour = ColourLayout(hsv, pixels, foreground);
  }
  const auto gradient = GradientHistogram(small, pixels, foreground);
  ScaleChannel(colour, soft ? kSoftColourNorm : kColourNorm,
               std::span<std::uint8_t>(values.data() + kColourChannelOffset, kColourChannelSize));
  ScaleChannel(
      gradient, kGradientNorm,
      std::span<std::uint8_t>(values.data() + kGradientChannelOffset, kGradientChannelSize));
}

}  // namespace orbit
