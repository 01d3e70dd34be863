#include "server/model_catalogue.h"

#include <stdexcept>

#include "storage/store_error.h"
#include "storage/view_index_loading.h"

namespace orbit::server {

ModelCatalogue::ModelCatalogue(ModelStore& store, DescriptorVariant variant,
                               ViewIndexOptions index_options)
    : store_(store), index_(LoadViewIndex(store, variant, index_options)) {}

ObjectSummary ModelCatalogue::Enroll(const Enrollment& enrollment) {
  if (enrollment.variant != variant()) {
    throw std::invalid_argument("enrollment variant " + std::string(VariantName(enrollment.variant)) +
                                " differs from the server's " + std::string(VariantName(variant())));
  }
  std::lock_guard lock(write_mutex_);
  const ObjectId id = store_.Enroll(enrollment);
  Reindex(id);
  return store_.Get(id)->summary;
}

ObjectSummary ModelCatalogue::AddViews(ObjectId id, const std::vector<ModelView>& views,
                                       const std::vector<std::string>& thumbnails) {
  std::lock_guard lock(write_mutex_);
  store_.AddViews(id, views, thumbnails);
  index_->Remove(id);
  Reindex(id);
  return store_.Get(id)->summary;
}

ObjectSummary ModelCatalogue::Delete(ObjectId id) {
  std::lock_guard lock(write_mutex_);
  std::optional<StoredObject> object = store_.Get(id);
  if (!object) throw StoreError(StoreError::Code::kNotFound, "no object with id " + std::to_string(id));
  store_.Delete(id);
  index_->Remove(id);
  return object->summary;
}

void ModelCatalogue::Reindex(ObjectId id) {
  std::optional<StoredObject> stored = store_.Get(id);
  if (!stored) return;  // deleted meanwhile by another store user; nothing to index
  ObjectModel model;
  model.id = id;
  model.name = stored->summary.name;
  model.variant = stored->summary.variant;
  model.views = std::move(stored->views);
  index_->Add(std::move(model));
}

}  // namespace orbit::server
