// Typical distance Ttyp of a model view (docs/design.md#typical-distance):
//   Ttyp(c_{i,f}) = mean T(c_{i,f}, c^noisy_{i,f})
// the mean Tanimoto distance between the view's CEDD and the CEDDs of its distorted copies. It
// says how far a query of this very view typically lands when the camera shakes or the sensor is
// noisy, so the rejection rule can judge a match's distance against it.
//
// The distorted copies are exactly two, the protocol's query distortions
// (core/descriptor/distortion.h):
//   1. MotionBlur(view)                                    15-pixel line at 20 degrees
//   2. AddGaussianNoise(view, kGaussianNoiseVariance, seed)  variance 0.012
// so Ttyp = (T(view, copy 1) + T(view, copy 2)) / 2.
//
// A view image's Ttyp, with its descriptor and the seed rule of its noisy copy, comes from
// DescribeView (core/descriptor/view_description.h). All functions are pure and thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <opencv2/core.hpp>

#include "core/descriptor/descriptor.h"

namespace orbit {

inline constexpr int kTypicalDistortionCount = 2;

// The distorted copies above, in that order. Throws as MotionBlur / AddGaussianNoise.
std::array<cv::Mat, kTypicalDistortionCount> TypicalDistortions(const cv::Mat& view,
                                                                std::uint64_t seed);

// Ttyp of a view given the CEDDs of its distorted copies (e.g. computed on a device, or reused
// from an evaluation's query images): the mean TanimotoDistance(view, copy).
// Throws std::invalid_argument when `copies` is empty.
double TypicalDistance(const DescriptorValues& view, std::span<const DescriptorValues> copies);

}  // namespace orbit
