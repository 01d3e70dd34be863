// SqliteModelStore: the embedded ModelStore, one SQLite file (docs/storage.md).
//
// Durability: write-ahead log with synchronous=FULL, so a method that returned has its change on
// disk and it survives a crash of the process or of the machine; every write is one
// BEGIN IMMEDIATE transaction, so a crash or an error mid-write leaves no trace of it.
//
// Concurrency: safe for concurrent use from many threads (ModelStore's contract). Writes go
// through one connection, one at a time; each reading thread gets a connection of its own from a
// small pool, so reads never wait for writes and see a committed snapshot. Other processes may
// open the same file: SQLite's locks keep one writer at a time, and a writer waits up to
// `busy_timeout` for another before failing with StoreError kBusy.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "core/base/mutex.h"
#include "storage/checkpoint_gate.h"
#include "storage/model_store.h"

namespace orbit {

class SqliteConnection;
class SqliteTransaction;

struct SqliteModelStoreOptions {
  // Otherwise a missing file is StoreError kIo. A created store, its log and its shared-memory
  // file are readable and writable by their owner only (storage/store_files.h).
  bool create_if_missing = false;
  std::chrono::milliseconds busy_timeout{5000};  // how long to wait for another writer
  bool quick_check_on_open = true;               // PRAGMA quick_check before anything else
  // After a commit that leaves at least this many pages (4 KiB each) in the write-ahead log, the
  // log is checkpointed into the database without waiting for readers. At four times this many
  // (readers kept those checkpoints from restarting the log) the writer holds this store's new
  // reads back, lets the reads in flight finish, and truncates the log (storage/checkpoint_gate.h):
  // the log cannot grow without bound. Readers in other processes are waited for 200 ms at most.
  int checkpoint_pages = 1000;
};

class SqliteModelStore final : public ModelStore {
 public:
  // Opens the store in `file`, creating it when asked; sets the durability pragmas, runs
  // PRAGMA quick_check and migrates the schema to kSchemaVersion (storage/schema.h).
  // Throws StoreError: kIo when the file cannot be opened (or is missing and not to be created),
  // kCorrupt when it is not a database or fails the check, kIncompatible when it is not an
  // Orbit store or is newer than this program.
  explicit SqliteModelStore(const std::filesystem::path& file,
                            const SqliteModelStoreOptions& options = {});
  ~SqliteModelStore() override;

  SqliteModelStore(const SqliteModelStore&) = delete;
  SqliteModelStore& operator=(const SqliteModelStore&) = delete;

  ObjectId Enroll(const Enrollment& enrollment) ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  void AddViews(ObjectId id, const std::vector<ModelView>& views,
                const std::vector<std::string>& thumbnails = {})
      ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  void Delete(ObjectId id) ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  void Rename(ObjectId id, std::string_view new_name) ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  std::vector<ObjectSummary> List(const ListRequest& request) override;
  std::optional<StoredObject> Get(ObjectId id) override;
  std::optional<ObjectSummary> Find(std::string_view name) override;
  std::vector<ObjectModel> LoadAll() override;
  // One read transaction on one pooled connection; writers carry on in the write-ahead log.
  ObjectId ForEachObject(const std::function<void(const StoredObject&)>& visit) override;
  void RestoreFrom(ModelStore& source) ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  // As ModelStore::Backup; the copy is created with the store file's own mode.
  void Backup(const std::filesystem::path& destination) override;

  const std::filesystem::path& file() const { return file_; }

 private:
  class Reader;  // a pooled read connection, returned to the pool when it goes out of scope

  // Commits a write and, when the log has grown enough, checkpoints it.
  void CommitWrite(SqliteTransaction& transaction) ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mutex_);

  const std::filesystem::path file_;
  const SqliteModelStoreOptions options_;

  Mutex write_mutex_;  // one writer, from its BEGIN to its checkpoint
  // Pages in the write-ahead log after the last commit: written by writer_'s WAL hook, which
  // runs inside a commit.
  int wal_pages_ ABSL_GUARDED_BY(write_mutex_) = 0;
  // Declared after wal_pages_: its hook points there.
  std::unique_ptr<SqliteConnection> writer_ ABSL_GUARDED_BY(write_mutex_);

  CheckpointGate checkpoint_gate_;  // every read is inside it
  Mutex readers_mutex_;             // held only to take or give back a connection
  std::vector<std::unique_ptr<SqliteConnection>> idle_readers_ ABSL_GUARDED_BY(readers_mutex_);
};

}  // namespace orbit
