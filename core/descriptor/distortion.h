// The image distortions of the evaluation protocol's MB and GN query images and of the typical
// distance (docs/design.md#distortions), defined exactly as the
// thesis' MATLAB code produced them:
//   MB  imfilter(I, fspecial('motion', 15, 20))
//   GN  imnoise(I, 'gaussian', 0, 0.012)
//
// Images are 8-bit with 1 to 4 channels (BGR, grey, BGRA); every channel is distorted on its
// own, as MATLAB does for an H x W x C array. All functions are pure and thread-safe.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace orbit {

inline constexpr double kMotionBlurLength = 15;          // pixels
inline constexpr double kMotionBlurAngleDegrees = 20;    // counter-clockwise from horizontal
inline constexpr double kGaussianNoiseVariance = 0.012;  // on the [0, 1] intensity scale

// The kernel of MATLAB's fspecial('motion', length, angle_degrees), reproduced step by step
// (same mesh, same end-of-line correction, same eps terms): a line `length` pixels long at
// `angle_degrees` counter-clockwise (as displayed, rows growing downward), anti-aliased over one
// pixel, normalised to sum 1 (to within length^2 * eps). CV_64FC1, odd width and height; for
// (15, 20) it is 7 rows x 15 columns.
// Throws std::invalid_argument when length or angle is not finite.
cv::Mat MotionBlurKernel(double length = kMotionBlurLength,
                         double angle_degrees = kMotionBlurAngleDegrees);

// imfilter(image, fspecial('motion', length, angle_degrees)) with imfilter's defaults:
// correlation with the kernel centred on each pixel, zero padding outside the image (so a
// bright object on black, like COIL-100, is blurred as if the black continued), output the same
// size and type, each value rounded to nearest (halves away from zero) and clamped to [0, 255].
// Throws std::invalid_argument when the image is empty or not 8-bit with 1-4 channels, or as
// MotionBlurKernel.
cv::Mat MotionBlur(const cv::Mat& image, double length = kMotionBlurLength,
                   double angle_degrees = kMotionBlurAngleDegrees);

// imnoise(image, 'gaussian', 0, variance): each value v becomes
// round(255 * clamp(v / 255 + sqrt(variance) * z, 0, 1)), with z independent N(0, 1) variates
// drawn from SeededRandom(seed) in row-major, channel-interleaved order. Equal seeds give equal
// images. variance 0 returns the image unchanged.
// Throws std::invalid_argument when the image is empty or not 8-bit with 1-4 channels, or when
// variance is negative or not finite.
cv::Mat AddGaussianNoise(const cv::Mat& image, double variance, std::uint64_t seed);

}  // namespace orbit
