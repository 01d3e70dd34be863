// ModelChangeFollower: keeps a replica's index in step with a PostgreSQL model store that other
// replicas write to (docs/scaling.md). It follows the store's change log in commit order: woken
// by LISTEN/NOTIFY (storage/postgres_change_listener.h) as soon as a change is committed, and
// reading the log at least every `poll_interval` anyway. Each change is applied by re-reading
// its object (ModelCatalogue::Reload), so applying one twice, or a change this replica made
// itself, is harmless and publishes nothing.
//
// Nothing is missed across a dropped connection or a restart of the database: the follower
// remembers the last seq it applied and, once the store answers again, replays the log from
// there. While the store cannot be reached it retries every `retry_interval`; when that lasts
// longer than `store_grace`, it reports the replica unfit to serve (health NOT_SERVING, so the
// balancer sends new sessions elsewhere: this replica's models may be stale), and fit again
// once it has caught up.
//
// The log is pruned (docs/design.md#change-log): after reading it, at most once a
// `poll_interval`, the follower reports the last seq it applied under its replica's name and
// deletes the changes every live replica has applied. A replica away for longer than
// `progress_lease` is not waited for; when it comes back and the changes it needs are gone
// (ChangeLogPruned), it reloads its whole index as at start-up instead of missing them.
//
// Thread-safe. The follower runs on a thread of its own from construction to destruction.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "core/base/mutex.h"
#include "storage/model_change.h"

namespace orbit {
class PostgresModelStore;
}

namespace orbit::server {

class ModelCatalogue;

struct ModelChangeFollowerOptions {
  std::chrono::milliseconds poll_interval{1000};  // read the log at least this often
  std::chrono::milliseconds retry_interval{500};  // between attempts while the store is away
  std::chrono::milliseconds store_grace{10000};   // away longer than this: unfit to serve
  // This replica's name among those of the database (replica_progress); empty: one made of the
  // host's name, the process id and a random number.
  std::string replica;
  // A replica silent for longer than this is not waited for when the log is pruned.
  std::chrono::milliseconds progress_lease{std::chrono::minutes(5)};
  // Called on the follower's thread with true when the replica becomes fit to serve again and
  // false when it stops being fit (never twice in a row with the same value).
  std::function<void(bool fit)> on_fitness = [](bool) {};
  // Called on the follower's thread with a line for the operator (lost and regained store, a
  // reload after the log was pruned past this replica).
  std::function<void(const std::string& message)> on_event = [](const std::string&) {};
  // Called on the follower's thread after a change changed the index (not for replays of what
  // the index already held).
  std::function<void(const ModelChange& change)> on_applied = [](const ModelChange&) {};
};

class ModelChangeFollower {
 public:
  // Follows the changes of `store` (reached through `conninfo` for LISTEN) committed after
  // `after_seq`, the seq read before `catalogue` was loaded (PostgresModelStore::
  // LatestChangeSeq). `store` and `catalogue` must outlive the follower.
  ModelChangeFollower(PostgresModelStore& store, std::string conninfo, ModelCatalogue& catalogue,
                      std::int64_t after_seq, ModelChangeFollowerOptions options = {});
  // Stops the thread (within about 100 ms; a change being applied is finished first).
  ~ModelChangeFollower();

  ModelChangeFollower(const ModelChangeFollower&) = delete;
  ModelChangeFollower& operator=(const ModelChangeFollower&) = delete;

  // The seq of the last change applied to the index.
  std::int64_t applied_seq() const { return applied_seq_.load(); }
  // Changes that made the index change (this replica's own writes, replayed, do not count).
  std::int64_t changes_applied() const { return changes_applied_.load(); }
  // Times the whole index was reloaded because the log was pruned past this replica.
  std::int64_t reloads() const { return reloads_.load(); }
  // The name this replica reports its progress under.
  const std::string& replica() const { return replica_; }

 private:
  void Run();
  // Applies every change after applied_seq_; returns when the log has no more.
  void CatchUp();
  // Loads every object again, as at start-up, when the changes after applied_seq_ are gone.
  void Reload(const ChangeLogPruned& pruned);
  // Reports applied_seq_ and prunes what every live replica has applied.
  void ReportProgress();
  // Sleeps up to `duration`; false when asked to stop meanwhile.
  bool SleepFor(std::chrono::milliseconds duration) ABSL_LOCKS_EXCLUDED(mutex_);
  bool Stopping() ABSL_LOCKS_EXCLUDED(mutex_);

  PostgresModelStore& store_;
  const std::string conninfo_;
  ModelCatalogue& catalogue_;
  const ModelChangeFollowerOptions options_;
  const std::string replica_;
  std::atomic<std::int64_t> applied_seq_;
  std::atomic<std::int64_t> changes_applied_{0};
  std::atomic<std::int64_t> reloads_{0};

  Mutex mutex_;
  CondVar wake_;
  bool stop_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread thread_;
};

}  // namespace orbit::server
