#include "api/conversion.h"

#include <cstdint>
#include <span>
#include <stdexcept>

namespace orbit {

v1::DescriptorVariant ToProtoVariant(DescriptorVariant variant) {
  switch (variant) {
    case DescriptorVariant::kCeddLire: return v1::CEDD_LIRE;
    case DescriptorVariant::kCeddFull: return v1::CEDD_FULL;
    case DescriptorVariant::kCeddRobust: return v1::CEDD_ROBUST;
    case DescriptorVariant::kCeddHsvHog: return v1::CEDD_HSV_HOG;
    case DescriptorVariant::kCeddHsvLayout: return v1::CEDD_HSV_LAYOUT;
    case DescriptorVariant::kCeddSoftHsvHog: return v1::CEDD_SOFT_HSV_HOG;
  }
  return v1::DESCRIPTOR_VARIANT_UNSPECIFIED;
}

DescriptorVariant FromProtoVariant(v1::DescriptorVariant variant) {
  switch (variant) {
    case v1::CEDD_LIRE: return DescriptorVariant::kCeddLire;
    case v1::CEDD_FULL: return DescriptorVariant::kCeddFull;
    case v1::CEDD_ROBUST: return DescriptorVariant::kCeddRobust;
    case v1::CEDD_HSV_HOG: return DescriptorVariant::kCeddHsvHog;
    case v1::CEDD_HSV_LAYOUT: return DescriptorVariant::kCeddHsvLayout;
    case v1::CEDD_SOFT_HSV_HOG: return DescriptorVariant::kCeddSoftHsvHog;
    default: throw std::invalid_argument("descriptor variant is " + ProtoVariantName(variant));
  }
}

std::string ProtoVariantName(v1::DescriptorVariant variant) {
  switch (variant) {
    case v1::CEDD_LIRE:
    case v1::CEDD_FULL:
    case v1::CEDD_ROBUST:
    case v1::CEDD_HSV_HOG:
    case v1::CEDD_HSV_LAYOUT:
    case v1::CEDD_SOFT_HSV_HOG: return std::string(VariantName(FromProtoVariant(variant)));
    case v1::DESCRIPTOR_VARIANT_UNSPECIFIED: return "unspecified";
    default: return "unknown (" + std::to_string(variant) + ")";
  }
}

DescriptorValues DescriptorFromWire(const std::string& cedd, const std::string& appearance,
                                    DescriptorVariant variant, std::string_view message) {
  const auto bytes = [](const std::string& text) {
    return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                         text.size());
  };
  const std::string prefix(message);
  DescriptorValues values =
      DescriptorFromBytes(bytes(cedd), DescriptorVariant::kCeddFull, prefix + ".cedd");
  const std::size_t expected = static_cast<std::size_t>(DescriptorLength(variant) - kCeddSize);
  if (appearance.size() != expected) {
    throw std::invalid_argument(prefix + ".appearance has " + std::to_string(appearance.size()) +
                                " values, expected " + std::to_string(expected) + " for " +
                                std::string(VariantName(variant)));
  }
  ValidateDescriptorValues(bytes(appearance), prefix + ".appearance");
  std::copy(appearance.begin(), appearance.end(), values.begin() + kCeddSize);
  return values;
}

void SetWireDescriptor(const DescriptorValues& values, DescriptorVariant variant, std::string* cedd,
                       std::string* appearance) {
  const std::span<const std::uint8_t> all = DescriptorBytes(values, variant);
  cedd->assign(all.begin(), all.begin() + kCeddSize);
  appearance->assign(all.begin() + kCeddSize, all.end());
}

v1::View ToProtoView(const ModelView& view, DescriptorVariant variant,
                     const std::string& thumbnail) {
  v1::View out;
  SetWireDescriptor(view.descriptor, variant, out.mutable_cedd(), out.mutable_appearance());
  out.set_azimuth_deg(view.azimuth);
  if (view.elevation) out.set_elevation_deg(*view.elevation);
  out.set_typical_distance(view.typical_distance);
  if (!thumbnail.empty()) out.set_thumbnail(thumbnail);
  return out;
}

}  // namespace orbit
