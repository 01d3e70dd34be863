// The appearance channels of the cedd-hsv-hog, cedd-hsv-layout and cedd-soft-hsv-hog variants
// (docs/design.md#appearance-channels, docs/design.md#colour-layout,
// docs/design.md#soft-hue-edges): what
// look-alike real objects need and CEDD lacks. CEDD's 24 coarse colour bins cannot tell a red
// apple from a redder one, and its texture classes move under blur; a finer colour histogram and
// a coarse layout of gradient orientations can.
//
// Both channels are taken from the region's canonical frame (core/descriptor/canonical_frame.h),
// resampled to kAppearanceSide x kAppearanceSide, so that they share CEDD's robustness to size,
// blur, noise and light:
//   colour    a hue x saturation x value histogram, 12 x 4 x 4 = 192 bins (bin =
//             hue_bin * 16 + saturation_bin * 4 + value_bin, OpenCV's 8-bit HSV; a dark pixel,
//             value bin 0, counts as hue 0 and saturation 0; a pixel of little chroma counts
//             only kSureChroma's share of its hue, the rest spread over every hue), less
//             the background's expected counts: the foreground estimate below;
//   gradient  unsigned gradient orientations, 9 bins over 0..180 degrees, in 4 x 4 cells of
//             16 x 16 pixels = 144 values (value = cell * 9 + orientation bin, cells row-major),
//             each pixel's magnitude split between its two nearest bins; each cell's histogram
//             is normalised as HOG's L2-Hys (L2, clipped at 0.2, L2 again), with a floor of
//             kFlatCellShare of the mean cell's norm added to each cell's; each pixel's
//             magnitude weighed by the object's share of its colour bin.
// cedd-hsv-layout keeps the gradient cells and replaces the colour histogram's 192 values with
//   colour layout  the object's colours in the frame's upper and lower halves, each a
//                  12 x 2 x 4 hue-saturation-value histogram (bin = hue_bin * 8 +
//                  saturation_bin * 4 + value_bin, 96 values a half, the upper half first), each
//                  pixel but a dark one (value bin 0, left out: how many each half holds follows
//                  the box) counted as the colour histogram counts it (kSureChroma) and
//                  weighed by the object's share of its colour-histogram bin (the foreground
//                  estimate, which stays that of the 192 bins).
// cedd-soft-hsv-hog is cedd-hsv-hog with
//   soft hue edges  a pixel whose hue lies within kHueEdgeReach of a bin's width from its hue
//                   bin's edge shares its hue count with the bin beyond: half at the edge,
//                   linearly less further in, none from kHueEdgeReach on;
//   its own weight  kSoftColourNorm for the colour histogram.
// Why: noise and compression move a hue by a few degrees; a hard edge turns that into a whole
// count moved to another bin, and an object whose colour lies on an edge into another object.
// Why: two look-alike objects differ in where their colours are (a cup's print, a cow's patches)
// more often than in which colours they hold; halves one above the other move little as the
// object turns about its vertical axis, the way a walk around it turns it.
// Each channel's square roots (a Hellinger-like scale: a bin's weight grows more slowly than its
// count) are scaled to the channel's energy (kColourNorm, kGradientNorm: its Euclidean norm) and
// rounded to 0..7, the range every descriptor value has. The channels' norms against CEDD's are
// what weighs them in the one Tanimoto coefficient the engines compute over the whole
// descriptor: the channel weights of docs/design.md#appearance-channels, chosen on held-out kinds
// of objects.
//
// Pure and thread-safe.
#pragma once

#include <opencv2/core.hpp>

#include "core/descriptor/descriptor.h"

namespace orbit {

inline constexpr int kAppearanceSide = 64;  // pixels a side the channels are taken at
inline constexpr int kHueBins = 12;
inline constexpr int kSaturationBins = 4;
inline constexpr int kValueBins = 4;
inline constexpr int kColourChannelSize = kHueBins * kSaturationBins * kValueBins;
inline constexpr int kGradientCellsPerSide = 4;
inline constexpr int kGradientOrientations = 9;
inline constexpr int kGradientChannelSize =
    kGradientCellsPerSide * kGradientCellsPerSide * kGradientOrientations;
inline constexpr int kColourChannelOffset = kCeddSize;
inline constexpr int kGradientChannelOffset = kColourChannelOffset + kColourChannelSize;
static_assert(kGradientChannelOffset + kGradientChannelSize == kDescriptorSize);

// cedd-hsv-layout's colour layout, in the colour histogram's place.
inline constexpr int kLayoutBands = 2;
inline constexpr int kLayoutSaturationBins = 2;
inline constexpr int kLayoutBandSize = kHueBins * kLayoutSaturationBins * kValueBins;
inline constexpr int kLayoutOffset = kColourChannelOffset;
static_assert(kLayoutBands * kLayoutBandSize == kColourChannelSize);

// Euclidean norm each channel is scaled to before rounding (values then clipped to 0..7).
inline constexpr double kColourNorm = 48.0;
inline constexpr double kSoftColourNorm = 40.0;  // cedd-soft-hsv-hog's
inline constexpr double kGradientNorm = 5.0;

// cedd-soft-hsv-hog: how far from a hue bin's edge, in bin widths, a pixel shares its hue count
// with the bin beyond (docs/design.md#soft-hue-edges); at most 0.5.
inline constexpr double kHueEdgeReach = 0.25;

// Chroma (max - min of a pixel's channels, 0..255) from which its hue counts in full
// (docs/design.md#appearance-channels).
inline constexpr double kSureChroma = 16.0;

// A gradient cell's normalisation adds this share of the mean cell's norm to its own
// (docs/design.md#appearance-channels), so that a flat cell stays small.
inline constexpr double kFlatCellShare = 0.5;

// The foreground estimate (docs/design.md#foreground-estimate): the ring of this many pixels
// along the 64x64 frame's edge is taken as background (it lies inside the margin a box is grown
// by); a colour is the ring's when it covers at least kCommonBorderColour of the ring; the
// background is taken to cover at most kMaxBackgroundShare of the frame.
inline constexpr int kBorderRing = 4;
inline constexpr double kCommonBorderColour = 0.02;
inline constexpr double kMaxBackgroundShare = 0.8;

// Writes the appearance channels of `variant` (HasAppearanceChannels) of `canonical` (8-bit BGR,
// not empty: a CanonicalFrame) into values[kColourChannelOffset, kDescriptorSize). Values before
// are left as they are. Throws std::invalid_argument for an empty image or one of another type,
// or a variant without appearance channels.
void AddAppearanceChannels(const cv::Mat& canonical, DescriptorVariant variant,
                           DescriptorValues& values);

}  // namespace orbit
