#include "storage/view_index_loading.h"

#include <string>
#include <utility>
#include <vector>

#include "storage/store_error.h"

namespace orbit {

std::optional<DescriptorVariant> StoreVariant(ModelStore& store) {
  const std::vector<ObjectSummary> first = store.List({.after_id = 0, .limit = 1});
  if (first.empty()) return std::nullopt;
  return first.front().variant;
}

std::vector<ObjectModel> LoadModels(ModelStore& store, DescriptorVariant variant) {
  std::vector<ObjectModel> models = store.LoadAll();
  for (const ObjectModel& model : models) {
    if (model.variant != variant) {
      throw StoreError(StoreError::Code::kIncompatible,
                       "the store holds object \"" + model.name + "\" (id " +
                           std::to_string(model.id) + ") in variant " +
                           std::string(VariantName(model.variant)) + ", not " +
                           std::string(VariantName(variant)));
    }
  }
  return models;
}

std::unique_ptr<ViewIndex> LoadViewIndex(ModelStore& store, DescriptorVariant variant,
                                         const ViewIndexOptions& options) {
  std::vector<ObjectModel> models = LoadModels(store, variant);
  if (models.empty()) return std::make_unique<ViewIndex>(variant, options);
  return std::make_unique<ViewIndex>(std::move(models), options);
}

}  // namespace orbit
