// Loading a model store into the engines' view index at start-up (core/index/view_index.h).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/index/view_index.h"
#include "storage/model_store.h"

namespace orbit {

// The variant of the objects `store` holds (that of its first object: LoadViewIndex refuses a
// mix), or nullopt for an empty store. What a server serves when not told a variant.
std::optional<DescriptorVariant> StoreVariant(ModelStore& store);

// Every object of `store` (ModelStore::LoadAll), checked to be of `variant`: what the index's
// bulk constructor and ViewIndex::ReplaceAll take. Throws StoreError kIncompatible, naming the
// first such object, when the store holds an object of another variant (docs/design.md#variants:
// never mix variants); other errors as ModelStore::LoadAll.
std::vector<ObjectModel> LoadModels(ModelStore& store, DescriptorVariant variant);

// A ViewIndex of every object in `store`, built in one pass from one snapshot (LoadModels) with
// the index's bulk constructor: one segment, one kd-tree. Adding the objects one by one instead
// makes the index merge its segments over and over (far slower in kd-tree mode: docs/storage.md,
// "Measured", `store-load-index-kdtree` against `index-add-loop-kdtree`). An
// empty store gives an empty index of `variant`. Throws as LoadModels and the ViewIndex
// constructor.
std::unique_ptr<ViewIndex> LoadViewIndex(ModelStore& store, DescriptorVariant variant,
                                         const ViewIndexOptions& options = {});

}  // namespace orbit
