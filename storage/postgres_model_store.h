// PostgresModelStore: the ModelStore on a PostgreSQL server (docs/storage.md, "PostgreSQL
// store"), so that several server replicas can share one store.
//
// Connection: a libpq connection string, "postgresql://user:password@host:port/dbname?..." or
// "host=... dbname=...". Messages name the target without its password (RedactedTarget).
//
// Durability: every write is one transaction and returns only once COMMIT has returned, so with
// the server's default synchronous_commit = on the change is in the server's write-ahead log on
// disk: it survives a crash of this process, of the database server or of its machine. A process
// killed mid-write leaves nothing of it (the server rolls back the dead session's transaction).
//
// Concurrency: safe for concurrent use from many threads (ModelStore's contract). Each call
// borrows a connection of its own from a small pool. Writes are serialised twice: one at a time
// in this process (a mutex), and one at a time across every process using the database (a
// transaction-scoped advisory lock, waited for up to `busy_timeout`, then StoreError kBusy).
// Reads never wait for writes: List and Find are one statement each, Get and LoadAll one
// REPEATABLE READ snapshot each.
//
// Change log: each write also appends one row to model_changes (seq, object_id, kind,
// committed_at) and sends NOTIFY orbit_model_changes with the row's seq as payload, both in the
// write's own transaction: a listener is told exactly when a change is committed, and the seqs
// are in commit order because the write lock is held until COMMIT. ChangesAfter reads the log.
// Replicas report how far they have applied it (ReportApplied) and prune what every live one has
// applied (PruneChanges); asked for changes that were pruned, ChangesAfter refuses rather than
// answer with a hole (docs/design.md#change-log).
//
// Errors: as ModelStore's. When the server is unreachable or goes away, StoreError kIo names the
// target and carries libpq's reason. One exception to "a method that throws has changed
// nothing": if the connection is lost during COMMIT itself, the write may or may not have been
// stored (the message says so; Find or Get tells which).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/mutex.h"
#include "storage/model_change.h"
#include "storage/model_store.h"

namespace orbit {

class PostgresConnection;

struct PostgresModelStoreOptions {
  std::chrono::milliseconds busy_timeout{5000};  // how long a write waits for another writer
  int max_idle_connections = 8;                  // connections kept open for reuse
};

// NOTIFY channel of the change log; the payload is the change's seq in decimal.
inline constexpr const char* kModelChangesChannel = "orbit_model_changes";

class PostgresModelStore final : public ModelStore {
 public:
  // Connects to `conninfo`, creates the tables in an empty schema and migrates the schema to
  // kPostgresSchemaVersion (storage/postgres_schema.h). Throws StoreError: kIo when the server
  // cannot be reached or refuses the connection (the message names the target and the server's
  // reason), kIncompatible when the schema holds something else or is newer than this program;
  // std::invalid_argument when `conninfo` is not a connection string.
  explicit PostgresModelStore(const std::string& conninfo,
                              const PostgresModelStoreOptions& options = {});
  ~PostgresModelStore() override;

  PostgresModelStore(const PostgresModelStore&) = delete;
  PostgresModelStore& operator=(const PostgresModelStore&) = delete;

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
  // One REPEATABLE READ READ ONLY transaction: replicas writing meanwhile are not seen.
  ObjectId ForEachObject(const std::function<void(const StoredObject&)>& visit) override;
  // Each restored object is also logged as an enrollment, so that replicas following this
  // database index it. The change log of `source`, if any, is not copied.
  void RestoreFrom(ModelStore& source) ABSL_LOCKS_EXCLUDED(write_mutex_) override;
  // A SQLite model store holding one ForEachObject snapshot, created readable by its owner only
  // (storage/store_files.h). The change log is not in it (docs/design.md#backup-and-restore).
  void Backup(const std::filesystem::path& destination) override;

  // The changes committed after the one numbered `after_seq` (0: from the start), in commit
  // order, at most `limit` (1..kMaxListLimit) of them: a follower calls it again with the last
  // seq it got until the answer is empty. Throws std::invalid_argument for a limit out of range,
  // ChangeLogPruned when changes after `after_seq` have been pruned (the log and the pruned point
  // are read in one snapshot, so an answer is never missing a change).
  std::vector<ModelChange> ChangesAfter(std::int64_t after_seq, int limit = 1000);

  // Records that `replica` (a name unique among the replicas of this database) has applied every
  // change through `applied_seq`, stamped with the database's clock. Until it has been silent for
  // longer than PruneChanges' lease, no change after `applied_seq` is pruned.
  void ReportApplied(std::string_view replica, std::int64_t applied_seq);

  // Deletes from the log every change that each replica which reported within `lease` has
  // applied, and forgets the replicas silent for longer (they are not waited for: back, they
  // get ChangeLogPruned). One statement: the deletion and the new pruned point commit together.
  // Returns the pruned point: the seq through which the log may no longer hold changes (0: none
  // pruned yet).
  std::int64_t PruneChanges(std::chrono::milliseconds lease);

  // The seq of the last change committed so far (0 when none; never below the pruned point,
  // which is the last committed change once everything is pruned). A follower reads it before
  // LoadAll and then follows from it: a change committed in between is applied again, which is
  // harmless because applying a change re-reads the object (server/model_change_follower.h).
  std::int64_t LatestChangeSeq();

  // The connection target without its password (for messages and the start-up account).
  const std::string& target() const { return target_; }

 private:
  class Lease;  // a pooled connection, returned to the pool when it goes out of scope

  const std::string conninfo_;
  const std::string target_;
  const PostgresModelStoreOptions options_;

  // One writer in this process, from its first statement to its COMMIT. Guards no field: what it
  // serialises is the use of the database.
  Mutex write_mutex_;

  // Held only to take or give back a connection (a write takes one while holding write_mutex_).
  Mutex pool_mutex_ ABSL_ACQUIRED_AFTER(write_mutex_);
  std::vector<std::unique_ptr<PostgresConnection>> idle_ ABSL_GUARDED_BY(pool_mutex_);
};

}  // namespace orbit
