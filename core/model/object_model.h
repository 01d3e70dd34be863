// A known object as the engines see it: a set of views, each a descriptor taken at a known
// azimuth (docs/design.md#notation: c_i is a set of views c_{i,f}).
//
// This is the vocabulary shared by core/ (index, engines), storage/ (the model store loads and
// saves it), server/ and the device, which sends its views in this form (api/conversion.h,
// ToProtoView): hence its own layer below the index, which a device does not link. Plain data;
// no invariants beyond the field comments.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/descriptor/descriptor.h"

namespace orbit {

// Stable identifier of an enrolled object (the model store's primary key); never reused.
using ObjectId = std::int64_t;

struct ModelView {
  DescriptorValues descriptor{};
  double azimuth = 0;               // degrees, normalised to [0, 360)
  std::optional<double> elevation;  // degrees, when the capture recorded it
  // Ttyp(c_{i,f}): mean Tanimoto distance between this view and its distorted copies
  // (docs/design.md#typical-distance); 0 when unknown.
  double typical_distance = 0;

  bool operator==(const ModelView&) const = default;
};

struct ObjectModel {
  ObjectId id = 0;
  std::string name;
  DescriptorVariant variant = DescriptorVariant::kCeddLire;  // every view has this variant
  std::vector<ModelView> views;

  bool operator==(const ObjectModel&) const = default;
};

}  // namespace orbit
