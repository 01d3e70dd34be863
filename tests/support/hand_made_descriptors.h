// Descriptors written by hand for the tests whose expected values are computed by hand: a few
// non-zero bins, every other bin 0.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <utility>

#include "core/descriptor/descriptor.h"

namespace orbit::testing {

// {bin, value} pairs; values 0..7.
inline DescriptorValues Bins(std::initializer_list<std::pair<int, int>> bins) {
  DescriptorValues values{};
  for (const auto& [bin, value] : bins) values[bin] = static_cast<std::uint8_t>(value);
  return values;
}

}  // namespace orbit::testing
