// FrameQuality: how useful a frame is to describe, measured cheaply on the device on the
// object's region: its sharpness and its noise.
//
// - sharpness: the variance of the Laplacian of the grey region (the "variance of Laplacian"
//   focus measure, Pech-Pacheco et al., ICPR 2000). Motion blur and defocus remove the fine
//   detail the Laplacian responds to, so a blurred frame reads several times lower than a sharp
//   one of the same scene. It depends on the scene's texture, so it is compared between frames
//   of one capture, never against a fixed number.
// - noise_sigma: core/descriptor/noise_estimate.h, in grey levels.
//
// Enrollment keeps, for each azimuth step, the sharpest usable frame; recognition sends every
// frame with its quality (Frame.quality, proto/orbit/v1/recognition.proto) for engines to weight.
// Pure and thread-safe.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "orbit/v1/recognition.pb.h"

namespace orbit {

struct FrameQuality {
  double sharpness = 0;    // variance of the Laplacian of the grey region, grey levels squared
  double noise_sigma = 0;  // estimated noise deviation, grey levels
  double blur = 0;         // 0 sharp .. 1 blurred (core/descriptor/blur_estimate.h)
};

// The quality of `image` (8-bit, 1, 3 or 4 channels), of `region` inside it when given.
// Throws std::invalid_argument for an empty image or a region not inside it.
FrameQuality MeasureFrameQuality(const cv::Mat& image,
                                 std::optional<cv::Rect> region = std::nullopt);

// When a frame of a capture is not worth describing (enrollment skips it).
struct FrameQualityLimits {
  // Below this fraction of the capture's median sharpness a frame is blurred: its texture bins
  // (half of CEDD) would describe the blur, not the object.
  double min_relative_sharpness = 0.35;
  // Above this noise (grey levels) the descriptor is dominated by noise; the evaluation's
  // strong noise (gn, variance 0.01 of the 0..1 range) reads well above it
  // (docs/results/recognition.md, "Noisy and blurred frames").
  double max_noise_sigma = 12;
};

// The least sharpness a frame of a capture whose frames measured `qualities` may have to be
// usable: limits.min_relative_sharpness times their median sharpness (0 for no frames).
double MinUsableSharpness(const std::vector<FrameQuality>& qualities,
                          const FrameQualityLimits& limits = {});

// Whether a frame of `quality` is usable in a capture whose MinUsableSharpness is
// `min_sharpness`.
bool IsUsableFrame(const FrameQuality& quality, double min_sharpness,
                   const FrameQualityLimits& limits = {});

v1::FrameQuality ToProtoFrameQuality(const FrameQuality& quality);

}  // namespace orbit
