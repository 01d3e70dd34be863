#include "core/descriptor.h"

namespace orbit {

std::string_view VariantName(DescriptorVariant variant) {
  switch (variant) {
    case DescriptorVariant::kCeddLire:
      return "cedd-lire";
    case DescriptorVariant::kCeddFull:
      return "cedd-full";
  }
  return "unknown";
}

std::optional<DescriptorVariant> ParseVariant(std::string_view name) {
  if (name == "cedd-lire") return DescriptorVariant::kCeddLire;
  if (name == "cedd-full") return DescriptorVariant::kCeddFull;
  return std::nullopt;
}

}  // namespace orbit
