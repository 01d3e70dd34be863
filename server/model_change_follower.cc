#include "server/model_change_follower.h"

#include <unistd.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "server/model_catalogue.h"
#include "storage/postgres_change_listener.h"
#include "storage/postgres_model_store.h"
#include "storage/store_error.h"

namespace orbit::server {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// How long one wait for a notification lasts at most: how promptly the thread sees a stop.
constexpr milliseconds kWaitSlice{100};

// Changes read from the log per query.
constexpr int kChangesPerRead = 1000;

// A name no other replica of the database has: host, process and a random number (a restarted
// process is a new replica; its predecessor's entry expires with the lease).
std::string NewReplicaName() {
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  std::random_device random;
  std::ostringstream name;
  name << host << '/' << ::getpid() << '/' << std::hex << random();
  return name.str();
}

}  // namespace

ModelChangeFollower::ModelChangeFollower(PostgresModelStore& store, std::string conninfo,
                                         ModelCatalogue& catalogue, std::int64_t after_seq,
                                         ModelChangeFollowerOptions options)
    : store_(store),
      conninfo_(std::move(conninfo)),
      catalogue_(catalogue),
      options_(std::move(options)),
      replica_(options_.replica.empty() ? NewReplicaName() : options_.replica),
      applied_seq_(after_seq),
      thread_([this] { Run(); }) {}

ModelChangeFollower::~ModelChangeFollower() {
  {
    MutexLock lock(&mutex_);
    stop_ = true;
  }
  wake_.SignalAll();
  thread_.join();
}

bool ModelChangeFollower::Stopping() {
  MutexLock lock(&mutex_);
  return stop_;
}

bool ModelChangeFollower::SleepFor(milliseconds duration) {
  const Clock::time_point deadline = Clock::now() + duration;
  MutexLock lock(&mutex_);
  while (!stop_ && wake_.WaitUntil(&mutex_, deadline)) {
  }
  return !stop_;
}

void ModelChangeFollower::CatchUp() {
  for (;;) {
    std::vector<ModelChange> changes;
    try {
      changes = store_.ChangesAfter(applied_seq_, kChangesPerRead);
    } catch (const ChangeLogPruned& pruned) {
      Reload(pruned);
      continue;
    }
    for (const ModelChange& change : changes) {
      try {
        if (catalogue_.Reload(change.object_id)) {
          ++changes_applied_;
          options_.on_applied(change);
        }
      } catch (const std::invalid_argument& e) {
        // The stored object cannot be indexed here (another variant, say): no retry will change
        // that, so it is reported and passed over rather than blocking every later change.
        options_.on_event("cannot apply change " + std::to_string(change.seq) + " (object " +
                          std::to_string(change.object_id) + "): " + e.what() + "; passed over");
      }
      applied_seq_ = change.seq;
    }
    if (static_cast<int>(changes.size()) < kChangesPerRead || Stopping()) return;
  }
}

void ModelChangeFollower::Reload(const ChangeLogPruned& pruned) {
  // As at start-up: the position first, then every object; a change committed in between is in
  // the index and is replayed harmlessly.
  const std::int64_t position = store_.LatestChangeSeq();
  catalogue_.Load();
  applied_seq_ = position;
  options_.on_event(std::string(pruned.what()) + ": reloaded every object as of change " +
                    std::to_string(position));
  ++reloads_;
}

void ModelChangeFollower::ReportProgress() {
  store_.ReportApplied(replica_, applied_seq_);
  store_.PruneChanges(options_.progress_lease);
}

void ModelChangeFollower::Run() {
  std::unique_ptr<PostgresChangeListener> listener;
  std::optional<Clock::time_point> away_since;  // when the store stopped answering
  bool fit = true;  // the server loaded its index before starting the follower
  std::optional<Clock::time_point> reported;  // when this replica last reported its progress
  while (!Stopping()) {
    try {
      // LISTEN before reading the log: a change committed after the read wakes the wait below.
      if (!listener) listener = std::make_unique<PostgresChangeListener>(conninfo_);
      CatchUp();
      if (!reported || Clock::now() - *reported >= options_.poll_interval) {
        ReportProgress();
        reported = Clock::now();
      }
      if (away_since) {
        options_.on_event("the model store answers again; caught up to change " +
                          std::to_string(applied_seq_));
        away_since.reset();
      }
      if (!fit) {
        fit = true;
        options_.on_fitness(true);
      }
      const Clock::time_point next_read = Clock::now() + options_.poll_interval;
      for (Clock::time_point now = Clock::now(); now < next_read && !Stopping();
           now = Clock::now()) {
        const auto left = std::chrono::duration_cast<milliseconds>(next_read - now);
        if (listener->Wait(std::min(kWaitSlice, std::max(left, milliseconds(1))))) break;
      }
    } catch (const StoreError& e) {
      listener.reset();  // a new connection, LISTENing afresh, on the next attempt
      const Clock::time_point now = Clock::now();
      if (!away_since) {
        away_since = now;
        options_.on_event(std::string("cannot follow the model store's changes: ") + e.what() +
                          "; retrying every " + std::to_string(options_.retry_interval.count()) +
                          " ms with the models as of change " + std::to_string(applied_seq_));
      }
      if (fit && now - *away_since >= options_.store_grace) {
        fit = false;
        options_.on_fitness(false);
        options_.on_event("the model store has been unreachable for more than " +
                          std::to_string(options_.store_grace.count()) +
                          " ms: reporting NOT_SERVING until it answers");
      }
      SleepFor(options_.retry_interval);
    }
  }
}

}  // namespace orbit::server
