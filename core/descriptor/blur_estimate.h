// EstimateBlur: how blurred a frame is, from the frame alone, in [0, 1] (0 sharp, 1 as blurred
// as blurring can make it), cheaply enough to run on every frame on the device (for the
// calibrated rule's allowance for blurred frames, core/decision/quality_allowance.h).
//
// Crété-Roffet, Dolmière, Ladret and Nicolas, "The blur effect: perception and estimation with
// a new no-reference perceptual blur metric", SPIE Electronic Imaging 2007. The grey image is
// blurred again with a 9-pixel box along one axis; a sharp frame loses much of its
// neighbour-to-neighbour variation, an already blurred one little:
//   D_F = |F(x, y) - F(x, y - 1)|,  D_B = |B(x, y) - B(x, y - 1)|   (B: F blurred vertically)
//   blur_vertical = (sum D_F - sum max(0, D_F - D_B)) / sum D_F
// the same horizontally, and the larger of the two (motion blur along one direction reads
// high). Unlike the variance of the Laplacian (client/frame_quality.h), the ratio does not
// depend on how much texture the scene has, so it is comparable across objects. Noise reads as
// sharpness: a noisy frame's blur is low whatever its blur (the readings on COIL-100:
// docs/results/recognition.md, "Noisy and blurred frames").
//
// Pure and thread-safe.
#pragma once

#include <opencv2/core.hpp>

namespace orbit {

inline constexpr int kBlurEstimateKernel = 9;  // pixels of the re-blurring box

// The blur of `image` (8-bit, 1, 3 or 4 channels; a 4th channel, alpha, is ignored). Returns 0
// for an image without variation (nothing to judge) or smaller than 2 x 2. Throws
// std::invalid_argument for an empty image or one of another type.
double EstimateBlur(const cv::Mat& image);

}  // namespace orbit
