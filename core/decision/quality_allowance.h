// The quality allowance of the calibrated accept / unknown rule: how much the
// unknown statistic U (core/decision/unknown_statistic.h) of an unknown object's window rises when
// its frames are noisy or blurred, taken off U so that the rule's target false-accept rate holds
// for degraded windows as it does for clean ones.
//
// Why: the rule's threshold is a quantile of a null of clean windows
// (core/decision/rejection_calibration.h) and the server cannot draw degraded ones (it holds
// descriptors, not images). Noise moves every frame away from every view, so U rises for
// unknown and known objects alike (for known ones faster still) and a single
// threshold rejects most noisy known objects (docs/results/recognition.md, "Noisy and blurred
// frames"); blur does the same, less strongly. The device measures each frame's
// noise and blur (Frame.quality, client/frame_quality.h); the rule then accepts
//
//   U - NoiseAllowance(mean noise sigma) - BlurAllowance(mean blur) <= threshold
//
// (means over the window's frames that carry a reading) and judges a window without readings
// as before.
//
//   NoiseAllowance(s) = per_grey_level * clamp(s - kCleanNoiseSigma, 0, kNoiseAllowanceSpan)
//
// The slope is the rise of the null's low quantile (at the default target rate) with the frames'
// measured noise, fitted over a sweep of noise strengths (variance 0.002..0.03) of the tuning
// split's unknown objects (every tenth object of COIL-100), once per descriptor variant, since U
// rises at each variant's own pace (AllowanceSlopes). It is the null's rise, not the known
// objects' (which is steeper): allowing that much accepted most of the tuning split's unknown
// objects at the strongest noise. Beyond the span measured, a frame claims no more. The fits:
// docs/results/recognition.md, "Noisy and blurred frames" (CEDD's variants), and
// docs/results/real-objects.md, "The product's variant" (cedd-hsv-hog).
//
// Pure and thread-safe.
#pragma once

#include <optional>
#include <span>

#include "core/descriptor/descriptor.h"
#include "core/descriptor/query_frame.h"

namespace orbit {

inline constexpr double kCleanNoiseSigma = 2;      // what clean frames read, at most
inline constexpr double kNoiseAllowanceSpan = 40;  // grey levels above it, at most

// The same for blur (core/descriptor/blur_estimate.h, in [0, 1]): motion or focus blur moves a
// frame away from every view too, and the device can read it from the frame alone.
//
//   BlurAllowance(b) = per_blur_unit * max(0, b - kSharpFrameBlur)
//
// fitted the same way, over a sweep of motion blur (5..25 px at changing angles), above 0.5,
// where sharp COIL-100 frames end (docs/results/recognition.md, "Noisy and blurred frames").
// Noise reads as sharpness and blur hides noise, so at most one of the two allowances is large
// for a frame. A smooth, textureless object
// reads somewhat blurred even when sharp, and is allowed a little.
inline constexpr double kSharpFrameBlur = 0.5;  // what sharp frames read, at most

// The two slopes, fitted for one descriptor variant (docs/design.md#quality-allowance).
struct AllowanceSlopes {
  double per_grey_level;  // U per grey level above kCleanNoiseSigma
  double per_blur_unit;   // U per unit of blur above kSharpFrameBlur
};

// CEDD's variants (fitted on cedd-robust, the product's variant then) and cedd-hsv-hog, whose
// slopes cedd-hsv-layout and cedd-soft-hsv-hog use too (not refitted for them:
// docs/results/real-objects.md).
inline constexpr AllowanceSlopes kCeddAllowanceSlopes = {0.006, 0.5};
inline constexpr AllowanceSlopes kHsvHogAllowanceSlopes = {0.005, 0.2};

// The slopes fitted for `variant`.
const AllowanceSlopes& AllowanceSlopesFor(DescriptorVariant variant);

// The known ceiling's allowance (core/decision/rejection_calibration.h): the ceiling is a high
// quantile of known objects' clean windows, and U rises with noise and blur faster for known
// objects than for unknown ones, so the ceiling is judged against U less the rise of the known
// objects' high quantile, fitted on the same sweeps (docs/design.md#known-ceiling).
inline constexpr AllowanceSlopes kCeddKnownAllowanceSlopes = {0.013, 1.5};
inline constexpr AllowanceSlopes kHsvHogKnownAllowanceSlopes = {0.017, 1.7};
const AllowanceSlopes& KnownAllowanceSlopesFor(DescriptorVariant variant);

// NoiseAllowance + BlurAllowance of a window's mean readings; a missing reading allows nothing.
double WindowAllowance(std::optional<double> noise_sigma, std::optional<double> blur,
                       const AllowanceSlopes& slopes);

// The formulas above. REQUIRES: noise_sigma in [0, kMaxNoiseSigma], blur in [0, kMaxBlur].
double NoiseAllowance(double noise_sigma, const AllowanceSlopes& slopes);
double BlurAllowance(double blur, const AllowanceSlopes& slopes);

// The mean of the readings that are present; nullopt when none is.
std::optional<double> MeanReading(std::span<const std::optional<double>> readings);

}  // namespace orbit
