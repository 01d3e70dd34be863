// CanonicalFrame: what the cedd-robust descriptor variant does to a region before CEDD, so that
// one object seen by different cameras, at different distances, shaken, noisy, compressed or
// under different light gives nearly the same descriptor (docs/design.md#canonical-frame;
// docs/results/robustness.md measures each step).
//
// Three steps, in this order:
//   1. Canonical size. The region is resampled to about kCanonicalArea pixels (128 x 128 for a
//      square region), keeping its aspect ratio: area averaging when shrinking, bilinear when
//      growing. Every later constant is in pixels of this size, so a 640 x 480 crop and a
//      128 x 128 crop of the same scene are treated alike.
//   2. Canonical blur. A Gaussian of deviation kCanonicalBlurSigma (2 px at the canonical size).
//      CEDD's texture classes come from differences between 2 x 2 quadrant means of small blocks
//      against fixed thresholds: sensor noise of a few grey levels pushes nearly every block over
//      them (a noisy frame's descriptor is all "edge"), while motion blur and JPEG blocking move
//      blocks the other way or add false edges. Blurring every frame, model and query alike,
//      removes the fine texture that none of these distortions preserves and keeps the
//      structure that they all do. A fixed deviation measured better than one adapted to the
//      frame's estimated noise (robustness.md, "Ablation").
//   3. Brightness normalisation. Every channel is scaled by kBrightnessTarget / p, where p is
//      the kBrightnessPercentile-th percentile of the brightest channel over the pixels brighter
//      than kDarkLevel (the object and a lit background; a black backdrop is left out). This
//      undoes a global gain (exposure, a dimmer or brighter room): CEDD's fuzzy colour bins
//      depend on brightness, so a frame at gain 0.6 otherwise matches other objects. Frames with
//      fewer than 1% such pixels (nearly black) are left as they are.
//
// Pure and thread-safe.
#pragma once

#include <opencv2/core.hpp>

namespace orbit {

inline constexpr int kCanonicalArea = 128 * 128;      // pixels after step 1
inline constexpr double kCanonicalBlurSigma = 2.0;    // pixels at the canonical size
inline constexpr int kDarkLevel = 20;                 // pixels at or below it are "black"
inline constexpr double kBrightnessPercentile = 0.9;  // of the brightest channel, in [0, 1]
inline constexpr int kBrightnessTarget = 200;         // where that percentile is moved

// The steps, each of which can be switched off to measure what it contributes (the ablation of
// docs/results/robustness.md: build/orbit_robustness_ablation). The defaults are cedd-robust's;
// the product never uses other values.
struct CanonicalFrameOptions {
  int area = kCanonicalArea;                // step 1; 0: the region keeps its size
  double blur_sigma = kCanonicalBlurSigma;  // step 2; 0: no blur
  bool normalise_brightness = true;         // step 3
};

// The canonical frame of `bgr` (8-bit, 3 channels, not empty): steps 1-3 above. The result is
// a new 8-bit BGR image, of about options.area pixels (each side at least 1).
// Throws std::invalid_argument for an empty image or one of another type.
cv::Mat CanonicalFrame(const cv::Mat& bgr, const CanonicalFrameOptions& options = {});

}  // namespace orbit
