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
//   NoiseAllowance(s) = kNoiseAllowancePerGreyLevel
//                       * clamp(s - kCleanNoiseSigma, 0, kNoiseAllowanceSpan)
//
// The slope is the rise of the null's 15% quantile (the default target rate when it was fitted)
// with the frames' measured noise, fitted over a sweep of noise strengths (variance
// 0.002..0.03) of the tuning split's unknown objects (every tenth object of COIL-100) and
// checked on the other split. The 17% quantile of today's default rises alike. It is the null's
// rise, not the known objects' (which is steeper): allowing that much accepted most of the
// tuning split's unknown objects at the strongest noise. Beyond the span measured, a frame
// claims no more. The fits: docs/results/recognition.md, "Noisy and blurred frames".
//
// Pure and thread-safe.
#pragma once

#include <optional>
#include <span>

#include "core/descriptor/query_frame.h"

namespace orbit {

inline constexpr double kCleanNoiseSigma = 2;                 // what clean frames read, at most
inline constexpr double kNoiseAllowancePerGreyLevel = 0.006;  // U per grey level above it
inline constexpr double kNoiseAllowanceSpan = 40;             // grey levels above it, at most

// The formula above. REQUIRES: noise_sigma in [0, kMaxNoiseSigma].
double NoiseAllowance(double noise_sigma);

// The same for blur (core/descriptor/blur_estimate.h, in [0, 1]): motion or focus blur moves a
// frame away from every view too, and the device can read it from the frame alone.
//
//   BlurAllowance(b) = kBlurAllowancePerUnit * max(0, b - kSharpFrameBlur)
//
// fitted the same way, over a sweep of motion blur (5..25 px at changing angles), above 0.5,
// where sharp COIL-100 frames end (docs/results/recognition.md, "Noisy and blurred frames").
// Noise reads as sharpness and blur hides noise, so at most one of the two allowances is large
// for a frame. A smooth, textureless object
// reads somewhat blurred even when sharp, and is allowed a little.
inline constexpr double kSharpFrameBlur = 0.5;        // what sharp frames read, at most
inline constexpr double kBlurAllowancePerUnit = 0.5;  // U per unit of blur above it

// The formula above. REQUIRES: blur in [0, kMaxBlur].
double BlurAllowance(double blur);

// The mean of the readings that are present; nullopt when none is.
std::optional<double> MeanReading(std::span<const std::optional<double>> readings);

}  // namespace orbit
