// ModelChangeFollower (server/model_change_follower.h) on a real PostgreSQL server: replica B's
// index follows what replica A writes, in order, through a dropped connection and a crash of
// the database server, and B reports itself unfit to serve only after the grace. The log is
// pruned only through what every live replica applied, and a replica back from beyond its lease
// reloads its whole index.
#include "server/model_change_follower.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "server/model_catalogue.h"
#include "storage/postgres_model_store.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/wait_until.h"

namespace orbit::server {
namespace {

using Clock = std::chrono::steady_clock;
using orbit::testing::SyntheticObject;
using orbit::testing::SyntheticView;
using orbit::testing::TestDatabase;
using orbit::testing::WaitUntil;
using std::chrono::milliseconds;

// A replica: its own store on the shared database, its catalogue, and its follower.
struct Replica {
  explicit Replica(const std::string& conninfo, ModelChangeFollowerOptions options = {})
      : store(conninfo),
        after_seq(store.LatestChangeSeq()),
        catalogue(store, DescriptorVariant::kCeddLire, {}) {
    catalogue.Load();
    follower = std::make_unique<ModelChangeFollower>(store, conninfo, catalogue, after_seq,
                                                     std::move(options));
  }

  // A copy of the object as the index holds it now: the follower may publish a new snapshot and
  // free the old one at any moment, so no pointer into a snapshot outlives this call.
  std::optional<ObjectModel> Find(ObjectId id) const {
    const std::shared_ptr<const ViewIndexSnapshot> snapshot = catalogue.Snapshot();
    const IndexedObject* object = snapshot->Find(id);
    if (object == nullptr) return std::nullopt;
    return object->model();
  }

  PostgresModelStore store;
  std::int64_t after_seq;
  ModelCatalogue catalogue;
  std::unique_ptr<ModelChangeFollower> follower;
};

TEST(PostgresModelChangeFollowerTest, ReplicaBFollowsEveryKindOfChangeReplicaACommits) {
  TestDatabase database;
  Replica a(database.conninfo());
  Replica b(database.conninfo());

  const ObjectSummary mug = a.catalogue.Enroll(SyntheticObject("mug", 4));
  ASSERT_TRUE(WaitUntil([&] { return b.Find(mug.id).has_value(); }));
  EXPECT_EQ(b.Find(mug.id), a.Find(mug.id));

  a.catalogue.AddViews(mug.id, {SyntheticView(50, 200)}, {});
  ASSERT_TRUE(WaitUntil([&] { return b.Find(mug.id)->views.size() == 5; }));
  a.store.Rename(mug.id, "cup");
  ASSERT_TRUE(WaitUntil([&] { return b.Find(mug.id)->name == "cup"; }));
  a.catalogue.Delete(mug.id);
  ASSERT_TRUE(WaitUntil([&] { return !b.Find(mug.id).has_value(); }));
  EXPECT_EQ(b.follower->changes_applied(), 4);

  // B's own write comes back through the log and changes nothing there; A learns of it.
  const ObjectSummary jar = b.catalogue.Enroll(SyntheticObject("jar", 3, 9));
  const std::uint64_t serial = b.catalogue.Snapshot()->serial();
  ASSERT_TRUE(WaitUntil([&] { return b.follower->applied_seq() == b.store.LatestChangeSeq(); }));
  EXPECT_EQ(b.catalogue.Snapshot()->serial(), serial);
  EXPECT_EQ(b.follower->changes_applied(), 4);
  ASSERT_TRUE(WaitUntil([&] { return a.Find(jar.id).has_value(); }));
}

// A change committed after the replica read the log's position but before it loaded its index
// is in the index and replayed harmlessly; one committed after loading is followed.
TEST(PostgresModelChangeFollowerTest, NothingCommittedAroundTheStartIsMissed) {
  TestDatabase database;
  PostgresModelStore writer(database.conninfo());
  PostgresModelStore store(database.conninfo());
  const std::int64_t after_seq = store.LatestChangeSeq();
  const ObjectId before_load = writer.Enroll(SyntheticObject("mug", 2));
  ModelCatalogue catalogue(store, DescriptorVariant::kCeddLire, {});
  catalogue.Load();
  const ObjectId after_load = writer.Enroll(SyntheticObject("jar", 2, 7));
  ModelChangeFollower follower(store, database.conninfo(), catalogue, after_seq);
  ASSERT_TRUE(WaitUntil([&] { return catalogue.Snapshot()->Find(after_load) != nullptr; }));
  EXPECT_NE(catalogue.Snapshot()->Find(before_load), nullptr);
  EXPECT_EQ(follower.changes_applied(), 1);
  EXPECT_EQ(follower.applied_seq(), store.LatestChangeSeq());
}

// The database ends every connection again and again while A enrolls: B's listener and pool
// reconnect and replay the log from the last change they applied, so B ends with every object.
TEST(PostgresModelChangeFollowerTest, DroppedConnectionsLoseNoChange) {
  TestDatabase database;
  ModelChangeFollowerOptions options;
  options.retry_interval = milliseconds(20);
  Replica a(database.conninfo());
  Replica b(database.conninfo(), options);

  std::vector<ObjectId> enrolled;
  for (int i = 0; i < 12; ++i) {
    enrolled.push_back(
        a.store.Enroll(SyntheticObject(std::string("o").append(std::to_string(i)), 2, i * 10)));
    if (i % 3 == 0) {
      // Every session of the database but this one, waiting until each has ended: A's pooled
      // connections are then seen closed and replaced on its next call.
      database.Execute(
          "SELECT pg_terminate_backend(pid, 5000) FROM pg_stat_activity "
          "WHERE datname = current_database() AND pid <> pg_backend_pid()");
    }
  }
  ASSERT_TRUE(WaitUntil([&] { return b.catalogue.Snapshot()->object_count() == enrolled.size(); }))
      << b.catalogue.Snapshot()->object_count() << " of " << enrolled.size();
  for (ObjectId id : enrolled) EXPECT_TRUE(b.Find(id).has_value()) << id;
  EXPECT_EQ(b.follower->applied_seq(), a.store.LatestChangeSeq());
}

// The database server crashes under the replicas: B carries on with the models it has, reports
// itself unfit only once the grace has passed, and once the server is back catches up with what
// was committed and is fit again. On a private server: the shared one serves other tests.
TEST(PostgresModelChangeFollowerTest, ARestartedDatabaseIsCaughtUpAndFitnessFollowsTheGrace) {
  const orbit::testing::PrivatePostgresServer server;
  const std::string conninfo = server.conninfo();

  std::mutex mutex;
  std::vector<bool> fitness;  // what B reported, in order
  ModelChangeFollowerOptions options;
  options.retry_interval = milliseconds(50);
  options.store_grace = milliseconds(1500);
  options.on_fitness = [&](bool fit) {
    std::lock_guard lock(mutex);
    fitness.push_back(fit);
  };
  const auto reported = [&] {
    std::lock_guard lock(mutex);
    return fitness;
  };
  Replica a(conninfo);
  Replica b(conninfo, options);
  const ObjectSummary mug = a.catalogue.Enroll(SyntheticObject("mug", 3));
  ASSERT_TRUE(WaitUntil([&] { return b.Find(mug.id).has_value(); }));

  const Clock::time_point crash = Clock::now();
  server.Crash();
  ASSERT_TRUE(WaitUntil([&] { return !reported().empty(); }));
  EXPECT_GE(Clock::now() - crash, milliseconds(1500));  // not before the grace
  EXPECT_EQ(reported(), std::vector<bool>{false});
  EXPECT_TRUE(b.Find(mug.id).has_value());  // still serving what it had

  server.Restart();
  const ObjectSummary jar = a.catalogue.Enroll(SyntheticObject("jar", 3, 5));
  ASSERT_TRUE(WaitUntil([&] { return b.Find(jar.id).has_value(); }));
  ASSERT_TRUE(WaitUntil([&] { return reported().size() == 2; }));
  EXPECT_EQ(reported(), (std::vector<bool>{false, true}));
}

// The name replica `follower` reports its progress under, quoted for SQL.
std::string Quoted(const ModelChangeFollower& follower) { return "'" + follower.replica() + "'"; }

// Two replicas follow: what both have applied leaves the log; while one is stopped but within its
// lease, what it has not applied stays, and it then catches up without reloading anything.
TEST(PostgresModelChangeFollowerTest, TheLogKeepsWhatALiveReplicaHasNotApplied) {
  TestDatabase database;
  ModelChangeFollowerOptions options;
  options.poll_interval = milliseconds(50);
  Replica a(database.conninfo(), options);
  Replica b(database.conninfo(), options);
  for (int i = 0; i < 3; ++i) a.catalogue.Enroll(SyntheticObject("o" + std::to_string(i), 2, i));
  ASSERT_TRUE(WaitUntil([&] { return b.catalogue.Snapshot()->object_count() == 3; }));
  ASSERT_TRUE(WaitUntil([&] { return database.Int("SELECT count(*) FROM model_changes") == 0; }));

  const std::string b_name = Quoted(*b.follower);
  ModelChangeFollowerOptions resumed = options;  // B comes back as itself
  resumed.replica = b.follower->replica();
  const std::int64_t b_applied = b.follower->applied_seq();
  ASSERT_TRUE(WaitUntil([&] {
    return database.Int("SELECT applied_seq FROM replica_progress WHERE replica = " + b_name) ==
           b_applied;
  }));
  b.follower.reset();  // B pauses, well within its lease
  for (int i = 3; i < 5; ++i) a.catalogue.Enroll(SyntheticObject("o" + std::to_string(i), 2, i));
  const std::int64_t latest = a.store.LatestChangeSeq();
  ASSERT_TRUE(WaitUntil([&] {
    return database.Int("SELECT applied_seq FROM replica_progress WHERE replica = " +
                        Quoted(*a.follower)) == latest;
  }));
  EXPECT_EQ(a.store.PruneChanges(options.progress_lease), b_applied);
  EXPECT_EQ(database.Int("SELECT count(*) FROM model_changes"), 2);

  b.follower = std::make_unique<ModelChangeFollower>(b.store, database.conninfo(), b.catalogue,
                                                     b_applied, resumed);
  ASSERT_TRUE(WaitUntil([&] { return b.catalogue.Snapshot()->object_count() == 5; }));
  EXPECT_EQ(b.follower->reloads(), 0);
  ASSERT_TRUE(WaitUntil([&] { return database.Int("SELECT count(*) FROM model_changes") == 0; }));
}

// B stops following for longer than its lease, and A prunes the log past it. Back, B finds the
// changes it needs gone and reloads its whole index, so it misses neither A's new object nor
// the deletion of one it held.
TEST(PostgresModelChangeFollowerTest, AReplicaBackFromBeyondItsLeaseReloadsItsWholeIndex) {
  TestDatabase database;
  std::mutex mutex;
  std::vector<std::string> events;  // what B told the operator
  ModelChangeFollowerOptions options;
  options.poll_interval = milliseconds(50);
  options.progress_lease = milliseconds(300);
  Replica a(database.conninfo(), options);
  Replica b(database.conninfo(), options);
  const ObjectSummary mug = a.catalogue.Enroll(SyntheticObject("mug", 3));
  ASSERT_TRUE(WaitUntil([&] { return b.Find(mug.id).has_value(); }));

  const std::int64_t b_applied = b.follower->applied_seq();
  b.follower.reset();
  a.catalogue.Delete(mug.id);
  const ObjectSummary jar = a.catalogue.Enroll(SyntheticObject("jar", 3, 5));
  ASSERT_TRUE(WaitUntil([&] {
    return database.Int("SELECT pruned_through FROM change_log_horizon") ==
           a.store.LatestChangeSeq();
  }));
  EXPECT_THROW(b.store.ChangesAfter(b_applied), ChangeLogPruned);

  options.on_event = [&](const std::string& event) {
    std::lock_guard lock(mutex);
    events.push_back(event);
  };
  b.follower = std::make_unique<ModelChangeFollower>(b.store, database.conninfo(), b.catalogue,
                                                     b_applied, options);
  ASSERT_TRUE(WaitUntil([&] { return b.follower->reloads() == 1; }));
  EXPECT_FALSE(b.Find(mug.id).has_value());
  EXPECT_EQ(b.Find(jar.id), a.Find(jar.id));
  EXPECT_EQ(b.follower->applied_seq(), a.store.LatestChangeSeq());
  std::lock_guard lock(mutex);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0], "the change log was pruned past change " + std::to_string(b_applied) +
                           " (through " + std::to_string(a.store.LatestChangeSeq()) +
                           "): reloaded every object as of change " +
                           std::to_string(a.store.LatestChangeSeq()));
}

}  // namespace
}  // namespace orbit::server
