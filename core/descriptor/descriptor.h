// A view's descriptor as the rest of the product sees it: up to kDescriptorSize values in 0..7,
// tagged with the variant of the extractor that produced it (docs/design.md#variants).
//
// Layout: values 0..143 are CEDD's histogram (docs/design.md#histogram): value i belongs to
// texture class i / 24 and fuzzy colour bin i % 24. Classes: 0 non-edge, 1 non-directional,
// 2 horizontal, 3 vertical, 4 diagonal 45, 5 diagonal 135. The CEDD variants stop there; the
// cedd-hsv-hog, cedd-hsv-layout and cedd-soft-hsv-hog variants append their appearance channels
// (core/descriptor/appearance_channels.h).
// Values past a variant's DescriptorLength are 0, so one Tanimoto over every value serves
// every variant.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace orbit {

inline constexpr int kCeddSize = 144;          // CEDD's histogram
inline constexpr int kDescriptorSize = 480;    // values a descriptor holds: the longest variant's
inline constexpr int kDescriptorMaxValue = 7;  // each value is quantised to 3 bits
inline constexpr int kColourBins = 24;         // fuzzy colour bins per texture class
inline constexpr int kTextureClasses = 6;

using DescriptorValues = std::array<std::uint8_t, kDescriptorSize>;

enum class DescriptorVariant {
  kCeddLire,  // bit-exact with the LIRE reference; reads only LIRE's grid of blocks
  kCeddFull,  // the same algorithm on a 40x40 grid covering every pixel of the region
  // cedd-full of the region's canonical frame (core/descriptor/canonical_frame.h: canonical size,
  // blur and brightness): the product's variant, robust to blur, noise, compression and light
  kCeddRobust,
  // cedd-robust's CEDD followed by the appearance channels of the same canonical frame
  // (core/descriptor/appearance_channels.h): the product's variant for real objects that look
  // alike (docs/design.md#appearance-channels)
  kCeddHsvHog,
  // cedd-hsv-hog with its colour histogram replaced by a colour layout: the object's colours in
  // the frame's upper and lower halves (core/descriptor/appearance_channels.h,
  // docs/design.md#colour-layout)
  kCeddHsvLayout,
  // cedd-hsv-hog whose colour histogram shares a pixel near a hue bin's edge with the bin
  // beyond, with its own channel weights (core/descriptor/appearance_channels.h,
  // docs/design.md#soft-hue-edges): the product's variant
  kCeddSoftHsvHog,
};
inline constexpr std::array<DescriptorVariant, 6> kDescriptorVariants = {
    DescriptorVariant::kCeddLire,      DescriptorVariant::kCeddFull,
    DescriptorVariant::kCeddRobust,    DescriptorVariant::kCeddHsvHog,
    DescriptorVariant::kCeddHsvLayout, DescriptorVariant::kCeddSoftHsvHog};

// Whether `variant` appends the appearance channels to CEDD (cedd-hsv-hog, cedd-hsv-layout,
// cedd-soft-hsv-hog):
// its descriptors are kDescriptorSize values and are taken from the canonical frame.
bool HasAppearanceChannels(DescriptorVariant variant);

// The variant's name as it appears on the command line, in the API and in the model store:
// "cedd-lire", "cedd-full", "cedd-robust", "cedd-hsv-hog", "cedd-hsv-layout" or
// "cedd-soft-hsv-hog".
std::string_view VariantName(DescriptorVariant variant);

// Inverse of VariantName; nullopt for any other text.
std::optional<DescriptorVariant> ParseVariant(std::string_view name);

// VariantName of every variant, in kDescriptorVariants' order (for --variant's check).
std::vector<std::string> VariantNames();

// The one check of descriptor values, used wherever values arrive from outside (the store, the
// index, the engines, the server's requests). Throws std::invalid_argument
// "<what> value V at index I is outside 0..7" for the first value out of range.
void ValidateDescriptorValues(std::span<const std::uint8_t> values,
                              std::string_view what = "descriptor");

// How many values a descriptor of `variant` has: kCeddSize for the CEDD variants, kDescriptorSize
// for those with appearance channels. A store's blob and the wire carry exactly these.
int DescriptorLength(DescriptorVariant variant);

// The descriptor held in `bytes` (a store's blob, a request's fields): exactly
// DescriptorLength(variant) values, each valid. Throws std::invalid_argument
// "<what> has N values, expected L", or as ValidateDescriptorValues.
DescriptorValues DescriptorFromBytes(std::span<const std::uint8_t> bytes, DescriptorVariant variant,
                                     std::string_view what = "descriptor");

// The first DescriptorLength(variant) values of `values`: what a store or the wire holds.
std::span<const std::uint8_t> DescriptorBytes(const DescriptorValues& values,
                                              DescriptorVariant variant);

struct Descriptor {
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  DescriptorValues values{};

  friend bool operator==(const Descriptor&, const Descriptor&) = default;
};

}  // namespace orbit
