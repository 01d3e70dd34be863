#include "core/descriptor/descriptor.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace orbit {

std::string_view VariantName(DescriptorVariant variant) {
  switch (variant) {
    case DescriptorVariant::kCeddLire: return "cedd-lire";
    case DescriptorVariant::kCeddFull: return "cedd-full";
    case DescriptorVariant::kCeddRobust: return "cedd-robust";
    case DescriptorVariant::kCeddHsvHog: return "cedd-hsv-hog";
    case DescriptorVariant::kCeddHsvLayout: return "cedd-hsv-layout";
    case DescriptorVariant::kCeddSoftHsvHog: return "cedd-soft-hsv-hog";
  }
  return "unknown";
}

std::optional<DescriptorVariant> ParseVariant(std::string_view name) {
  for (const DescriptorVariant variant : kDescriptorVariants) {
    if (name == VariantName(variant)) return variant;
  }
  return std::nullopt;
}

std::vector<std::string> VariantNames() {
  std::vector<std::string> names;
  for (const DescriptorVariant variant : kDescriptorVariants) {
    names.emplace_back(VariantName(variant));
  }
  return names;
}

void ValidateDescriptorValues(std::span<const std::uint8_t> values, std::string_view what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] > kDescriptorMaxValue) {
      throw std::invalid_argument(std::string(what) + " value " + std::to_string(values[i]) +
                                  " at index " + std::to_string(i) + " is outside 0.." +
                                  std::to_string(kDescriptorMaxValue));
    }
  }
}

bool HasAppearanceChannels(DescriptorVariant variant) {
  return variant == DescriptorVariant::kCeddHsvHog ||
         variant == DescriptorVariant::kCeddHsvLayout ||
         variant == DescriptorVariant::kCeddSoftHsvHog;
}

int DescriptorLength(DescriptorVariant variant) {
  return HasAppearanceChannels(variant) ? kDescriptorSize : kCeddSize;
}

DescriptorValues DescriptorFromBytes(std::span<const std::uint8_t> bytes, DescriptorVariant variant,
                                     std::string_view what) {
  const int length = DescriptorLength(variant);
  if (bytes.size() != static_cast<std::size_t>(length)) {
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(bytes.size()) +
                                " values, expected " + std::to_string(length));
  }
  ValidateDescriptorValues(bytes, what);
  DescriptorValues values{};
  std::copy(bytes.begin(), bytes.end(), values.begin());
  return values;
}

std::span<const std::uint8_t> DescriptorBytes(const DescriptorValues& values,
                                              DescriptorVariant variant) {
  return std::span<const std::uint8_t>(values.data(),
                                       static_cast<std::size_t>(DescriptorLength(variant)));
}

}  // namespace orbit
