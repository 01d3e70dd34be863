// ModelStore: where the server keeps its object models between runs
// (docs/design.md#service-behaviour: enrollment is atomic and durable).
//
// An abstract interface so that a networked database (storage/postgres_model_store.h) can
// replace the embedded SQLite store (storage/sqlite_model_store.h) without touching core/. Every
// implementation keeps the contracts written here; tests/storage/model_store_test.cc checks
// them on each.
//
// Thread safety: an implementation is safe for concurrent use from many threads without external
// synchronisation. Writes are serialised (one writer); reads run beside them and see only whole,
// committed objects.
//
// Errors: bad arguments (see storage/model_validation.h for the exact rules) throw
// std::invalid_argument and write nothing; everything else throws StoreError
// (storage/store_error.h). A method that throws has changed nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/model/object_model.h"

namespace orbit {

// An object to enroll: its name, the variant of all its descriptors, its views and the extras
// the engines do not need.
struct Enrollment {
  std::string name;
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  std::vector<ModelView> views;  // at least one; azimuths are normalised to [0, 360) when stored
  // Empty, or one per view: a small encoded image (JPEG, PNG, ...) of the view; "" for none.
  std::vector<std::string> thumbnails;
  std::string metadata = "{}";  // free-form JSON object text
};

// One object as listed: everything but its views.
struct ObjectSummary {
  ObjectId id = 0;
  std::string name;
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  std::int64_t view_count = 0;
  std::string created_at;  // UTC, ISO 8601 with milliseconds: "2024-05-01T12:34:56.789Z"
  std::string updated_at;  // changes on rename and when views are added
  std::string metadata;    // JSON object text

  bool operator==(const ObjectSummary&) const = default;
};

// One object with its views, ordered by azimuth (then by the order they were stored).
struct StoredObject {
  ObjectSummary summary;
  std::vector<ModelView> views;
  std::vector<std::string> thumbnails;  // one per view, "" where the view has none

  bool operator==(const StoredObject&) const = default;
};

// One page of ListObjects: objects ordered by id, the first one's id greater than `after_id`.
struct ListRequest {
  ObjectId after_id = 0;  // 0 for the first page, then the id of the last object of a page
  int limit = 100;        // 1..kMaxListLimit objects per page
};
inline constexpr int kMaxListLimit = 10000;

class ModelStore {
 public:
  virtual ~ModelStore() = default;

  // Stores the object with all its views in one transaction: when it returns, the object is
  // durable (it survives a crash or power loss); when it throws, nothing of it was written.
  // Returns the new object's id, never an id used before (not even one of a deleted object).
  // Throws StoreError kAlreadyExists when the name is taken.
  virtual ObjectId Enroll(const Enrollment& enrollment) = 0;

  // Adds views to an existing object in one transaction, all or nothing; `thumbnails` is empty or
  // one per view. Throws StoreError kNotFound for an unknown id, std::invalid_argument when the
  // object would have more than kMaxViewsPerObject views.
  virtual void AddViews(ObjectId id, const std::vector<ModelView>& views,
                        const std::vector<std::string>& thumbnails = {}) = 0;

  // Deletes the object and all its views. Throws StoreError kNotFound for an unknown id.
  virtual void Delete(ObjectId id) = 0;

  // Renames the object (renaming to its current name does nothing). Throws StoreError kNotFound
  // for an unknown id, kAlreadyExists when another object has `new_name`.
  virtual void Rename(ObjectId id, std::string_view new_name) = 0;

  // One page of objects with their view counts, ordered by id; an empty page means the end.
  // Pages stay consistent under concurrent writes: no object is listed twice, and an object
  // present throughout the listing is listed once.
  virtual std::vector<ObjectSummary> List(const ListRequest& request) = 0;

  // The object with that id / name with all its views and thumbnails; nullopt when absent.
  virtual std::optional<StoredObject> Get(ObjectId id) = 0;
  virtual std::optional<ObjectSummary> Find(std::string_view name) = 0;

  // Every object with its views (no thumbnails, no metadata), ordered by id, views by azimuth:
  // what the engines index at start-up. One consistent snapshot.
  virtual std::vector<ObjectModel> LoadAll() = 0;

  // Hands every object, with its views and thumbnails as Get gives them, to `visit`, one at a
  // time in id order, all from one consistent snapshot while writers carry on: a write is seen
  // whole or not at all (docs/design.md#backup-and-restore). Returns the highest object id the
  // store has handed out, deleted objects' included (read at the snapshot or later, so never
  // lower), for a copy never to hand those out again. Throws what `visit` throws, and StoreError
  // as LoadAll.
  virtual ObjectId ForEachObject(const std::function<void(const StoredObject&)>& visit) = 0;

  // Copies every object of `source` (its ForEachObject) into this store, which must hold no
  // object, in one transaction: ids, names, variants, times, metadata, views and thumbnails as
  // they are there, and no id `source` handed out is handed out here afterwards. Throws StoreError
  // kAlreadyExists when this store holds objects, std::invalid_argument when an object breaks
  // storage/model_validation.h, and what `source` throws; this store is then unchanged.
  virtual void RestoreFrom(ModelStore& source) = 0;

  // Writes a consistent copy of the whole store to `destination` while the store stays in use
  // (readers and the writer carry on): a SQLite model store (storage/sqlite_model_store.h)
  // whichever store is copied. The copy appears atomically: `destination` is either its previous
  // self or the complete copy, and it is replaced if it exists. Throws std::invalid_argument
  // when `destination` is the store itself.
  virtual void Backup(const std::filesystem::path& destination) = 0;
};

}  // namespace orbit
