#include "server/model_catalogue.h"

#include <chrono>
#include <stdexcept>

#include "storage/store_error.h"
#include "storage/view_index_loading.h"

namespace orbit::server {
namespace {

using Clock = std::chrono::steady_clock;

// A store write that returned, begun at `start`: its duration, in `seconds` when there is one.
void ObserveWrite(prometheus::Histogram* seconds, Clock::time_point start) {
  if (seconds == nullptr) return;
  seconds->Observe(std::chrono::duration<double>(Clock::now() - start).count());
}

}  // namespace

ModelCatalogue::ModelCatalogue(ModelStore& store, DescriptorVariant variant,
                               ViewIndexOptions index_options, StoreWriteHistograms write_seconds)
    : store_(store),
      index_(std::make_unique<ViewIndex>(variant, index_options)),
      write_seconds_(write_seconds) {}

void ModelCatalogue::Load() {
  MutexLock lock(&write_mutex_);
  index_->ReplaceAll(LoadModels(store_, variant()));
}

ObjectSummary ModelCatalogue::Enroll(const Enrollment& enrollment) {
  if (enrollment.variant != variant()) {
    throw std::invalid_argument(
        "enrollment variant " + std::string(VariantName(enrollment.variant)) +
        " differs from the server's " + std::string(VariantName(variant())));
  }
  MutexLock lock(&write_mutex_);
  const Clock::time_point start = Clock::now();
  const ObjectId id = store_.Enroll(enrollment);
  ObserveWrite(write_seconds_.enroll, start);
  return Reindex(id);
}

ObjectSummary ModelCatalogue::AddViews(ObjectId id, const std::vector<ModelView>& views,
                                       const std::vector<std::string>& thumbnails) {
  MutexLock lock(&write_mutex_);
  const Clock::time_point start = Clock::now();
  store_.AddViews(id, views, thumbnails);
  ObserveWrite(write_seconds_.add_views, start);
  return Reindex(id);
}

ObjectSummary ModelCatalogue::Delete(ObjectId id) {
  MutexLock lock(&write_mutex_);
  std::optional<StoredObject> object = store_.Get(id);
  if (!object) throw ObjectNotFound(id);
  const Clock::time_point start = Clock::now();
  store_.Delete(id);
  ObserveWrite(write_seconds_.remove, start);
  index_->Remove(id);
  return object->summary;
}

bool ModelCatalogue::Reload(ObjectId id) {
  MutexLock lock(&write_mutex_);
  std::optional<StoredObject> stored = store_.Get(id);
  if (!stored) return index_->Remove(id);
  ObjectModel model{.id = id,
                    .name = stored->summary.name,
                    .variant = stored->summary.variant,
                    .views = std::move(stored->views)};
  const std::shared_ptr<const ViewIndexSnapshot> current = index_->Snapshot();
  if (const IndexedObject* indexed = current->Find(id); indexed && indexed->model() == model) {
    return false;
  }
  index_->Replace(std::move(model));
  return true;
}

ObjectSummary ModelCatalogue::Reindex(ObjectId id) {
  std::optional<StoredObject> stored = store_.Get(id);
  if (!stored) {
    // Another user of the store deleted it between our write and this read: the store is the
    // truth, so the index forgets it too.
    index_->Remove(id);
    throw StoreError(StoreError::Code::kNotFound,
                     "object " + std::to_string(id) + " was deleted meanwhile");
  }
  ObjectModel model;
  model.id = id;
  model.name = stored->summary.name;
  model.variant = stored->summary.variant;
  model.views = std::move(stored->views);
  index_->Replace(std::move(model));
  return stored->summary;
}

}  // namespace orbit::server
