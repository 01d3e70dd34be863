// ModelCatalogue: the server's objects, durable in a ModelStore and searchable in a ViewIndex,
// kept in step. A write goes to the store first (when it returns, the object survives a crash)
// and then to the index, so every session sees it from its next frame on
// (docs/design.md#service-behaviour). Each change reaches the index as one snapshot
// (ViewIndex::Replace, Remove): a frame never ranks without an object that is merely gaining
// views.
//
// Thread-safe: writes are serialised among themselves; reads (Snapshot, store reads) run beside
// them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/mutex.h"
#include "core/index/view_index.h"
#include "server/server_metrics.h"
#include "storage/model_store.h"

namespace orbit::server {

class ModelCatalogue {
 public:
  // A catalogue of `store` whose index is empty until Load(). Each committed store write is
  // observed, in seconds, in the histogram of `write_seconds` for its operation (none when
  // null); a write that throws is not.
  ModelCatalogue(ModelStore& store, DescriptorVariant variant, ViewIndexOptions index_options,
                 StoreWriteHistograms write_seconds = {});

  // Indexes every object of the store in one pass (storage/view_index_loading.h: LoadModels),
  // published as one snapshot in place of whatever the index held. Throws StoreError
  // kIncompatible when the store holds an object of another variant (naming it), and as
  // ModelStore::LoadAll; the index is then unchanged.
  void Load() ABSL_LOCKS_EXCLUDED(write_mutex_);

  // Each throws as the ModelStore method of the same name (StoreError kNotFound for an unknown
  // id), std::invalid_argument when the enrollment's variant is not the catalogue's, and
  // StoreError kNotFound when another user of the store deleted the object before it could be
  // read back. Return the object as stored.
  ObjectSummary Enroll(const Enrollment& enrollment) ABSL_LOCKS_EXCLUDED(write_mutex_);
  ObjectSummary AddViews(ObjectId id, const std::vector<ModelView>& views,
                         const std::vector<std::string>& thumbnails)
      ABSL_LOCKS_EXCLUDED(write_mutex_);
  ObjectSummary Delete(ObjectId id) ABSL_LOCKS_EXCLUDED(write_mutex_);

  // Makes the index agree with the store about object `id` after another writer changed it
  // (a replica following the change log: server/model_change_follower.h): publishes the stored
  // object, or drops it when the store no longer has it. Publishes nothing when the index
  // already holds exactly what is stored (this server's own writes, replayed), so sessions and
  // the rejection calibration redo nothing for them. Returns true when the index changed.
  // Throws StoreError as ModelStore::Get (the index is then unchanged).
  bool Reload(ObjectId id) ABSL_LOCKS_EXCLUDED(write_mutex_);

  std::shared_ptr<const ViewIndexSnapshot> Snapshot() const { return index_->Snapshot(); }

  // Work on every new snapshot before sessions see it (ViewIndex::PrepareSnapshotsWith): on the
  // thread that writes, i.e. an enrollment's bulk worker, not a session's frame.
  void PrepareSnapshotsWith(ViewIndex::SnapshotPreparation prepare) {
    index_->PrepareSnapshotsWith(std::move(prepare));
  }

  ModelStore& store() { return store_; }
  DescriptorVariant variant() const { return index_->variant(); }

 private:
  // Re-reads one object from the store and publishes it in the index in one snapshot; returns
  // its summary. Throws StoreError kNotFound (after dropping it from the index) when it is gone.
  ObjectSummary Reindex(ObjectId id) ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mutex_);

  ModelStore& store_;
  std::unique_ptr<ViewIndex> index_;
  const StoreWriteHistograms write_seconds_;
  // Held across a store write and the index change that follows it, so that the index takes the
  // changes in the store's order. Guards no field: store_ and index_ are thread-safe, and their
  // own locks are taken inside this one.
  Mutex write_mutex_;
};

}  // namespace orbit::server
