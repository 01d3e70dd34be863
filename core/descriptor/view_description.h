// DescribeView: what a model view stores, computed from its image. The one way a view is
// described for enrollment, whichever path enrolls it (the client library on a device, the
// server from an uploaded image, `orbit import`, the evaluation harness), so that the same image
// stores the same numbers through every path (docs/design.md#typical-distance: a device that
// sends descriptors without images computes the distorted copies itself).
//
// The seed rule. The Gaussian noise of a view's noisy copy (core/descriptor/typical_distance.h) is
// seeded from the view itself:
//   ViewNoiseSeed(descriptor, base) = MixSeed(base, FNV-1a 64 of the 144 CEDD values)
// with base = kDefaultViewNoiseSeed unless a caller asks otherwise (`orbit import --seed`,
// EnrollerOptions::seed, `orbit eval --seed`). It depends on neither the object's name, nor the
// view's position, nor the thread count, nor the platform's std::hash; two views with equal
// descriptors get equal noise, which is harmless (their copies are as alike as they are).
//
// All functions are pure and thread-safe.
#pragma once

#include <array>
#include <cstdint>

#include <opencv2/core.hpp>

#include "core/descriptor/descriptor.h"
#include "core/descriptor/typical_distance.h"

namespace orbit {

inline constexpr std::uint64_t kDefaultViewNoiseSeed = 1;

// The seed of the noisy copy of the view whose CEDD is `descriptor` (the rule above).
std::uint64_t ViewNoiseSeed(const DescriptorValues& descriptor,
                            std::uint64_t base = kDefaultViewNoiseSeed);

struct ViewDescription {
  DescriptorValues descriptor{};  // CEDD of the view
  // CEDDs of TypicalDistortions(view, ViewNoiseSeed(descriptor, base)), in that order: the
  // motion-blurred copy, then the noisy one.
  std::array<DescriptorValues, kTypicalDistortionCount> distorted{};
  double typical_distance = 0;  // Ttyp = TypicalDistance(descriptor, distorted), in [0, 1]
};

// Describes `view` (the object's region, already cropped) in `variant`.
// Throws std::invalid_argument as ExtractCedd and TypicalDistortions do (e.g. an empty image).
ViewDescription DescribeView(const cv::Mat& view, DescriptorVariant variant,
                             std::uint64_t base_seed = kDefaultViewNoiseSeed);

}  // namespace orbit
