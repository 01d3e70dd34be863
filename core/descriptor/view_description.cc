#include "core/descriptor/view_description.h"

#include "core/base/seeded_random.h"
#include "core/descriptor/cedd.h"

namespace orbit {
namespace {

// FNV-1a, 64 bits: a byte-order- and platform-independent hash of the descriptor's CEDD values.
std::uint64_t Fnv1a64(const DescriptorValues& values) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (int i = 0; i < kCeddSize; ++i) {
    const std::uint8_t value = values[i];
    hash ^= value;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

}  // namespace

std::uint64_t ViewNoiseSeed(const DescriptorValues& descriptor, std::uint64_t base) {
  return MixSeed(base, Fnv1a64(descriptor));
}

ViewDescription DescribeView(const cv::Mat& view, DescriptorVariant variant,
                             std::uint64_t base_seed) {
  ViewDescription description;
  description.descriptor = ExtractCedd(view, variant).values;
  const auto copies = TypicalDistortions(view, ViewNoiseSeed(description.descriptor, base_seed));
  for (int i = 0; i < kTypicalDistortionCount; ++i) {
    description.distorted[i] = ExtractCedd(copies[i], variant).values;
  }
  description.typical_distance = TypicalDistance(description.descriptor, description.distorted);
  return description;
}

}  // namespace orbit
