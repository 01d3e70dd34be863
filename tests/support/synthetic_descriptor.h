// Synthetic descriptors of the product's variant, for tests of the service (admission, limits,
// metrics, paging) that need frames and views a server takes, not described images. A server
// with a new store serves the product's variant, so these match it whichever variant that is.
#pragma once

#include "api/conversion.h"
#include "core/descriptor/descriptor.h"
#include "core/engines/product_pipeline.h"

namespace orbit::testing {

// A descriptor of the product's variant whose values in 0..7 differ with `seed`.
inline DescriptorValues SyntheticDescriptor(int seed) {
  DescriptorValues values{};
  for (int i = 0; i < DescriptorLength(Product().variant); ++i) {
    values[i] = static_cast<std::uint8_t>((i * 7 + seed * 3) % 8);
  }
  return values;
}

// A descriptor of the product's variant whose every value is `value` (0..7).
inline DescriptorValues UniformDescriptor(int value) {
  DescriptorValues values{};
  for (int i = 0; i < DescriptorLength(Product().variant); ++i) {
    values[i] = static_cast<std::uint8_t>(value);
  }
  return values;
}

// Puts `values` (of the product's variant) into `message`, a v1::Frame or v1::View: its `cedd`
// field and, where the variant has more, its `appearance` field.
template <class Message>
void SetDescriptor(Message& message, const DescriptorValues& values) {
  SetWireDescriptor(values, Product().variant, message.mutable_cedd(),
                    message.mutable_appearance());
}

}  // namespace orbit::testing
