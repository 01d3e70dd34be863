// What only the PostgreSQL store does: the change log, its notifications and its pruning, a
// backup as a SQLite file, the write lock
// shared by every process using the database, clear errors for an unreachable or refusing
// server, and atomic writes when the database fails one half-way. The contracts it shares with
// the SQLite store run on both in tests/storage/model_store_test.cc.
#include "storage/postgres_model_store.h"

#include <poll.h>

#include <atomic>
#include <chrono>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/postgres_connection.h"
#include "storage/postgres_transaction.h"
#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::StoreErrorOf;
using testing::SyntheticObject;
using testing::SyntheticView;
using testing::TestDatabase;

// The (object, kind) of each change, in the order given.
std::vector<std::pair<ObjectId, ModelChangeKind>> Kinds(const std::vector<ModelChange>& changes) {
  std::vector<std::pair<ObjectId, ModelChangeKind>> kinds;
  for (const ModelChange& change : changes) kinds.emplace_back(change.object_id, change.kind);
  return kinds;
}

TEST(PostgresModelStoreTest, ChangesAfterListsEachCommittedWriteInOrderUpToTheLatest) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  EXPECT_EQ(store.LatestChangeSeq(), 0);
  const ObjectId mug = store.Enroll(SyntheticObject("mug", 2));
  const ObjectId jar = store.Enroll(SyntheticObject("jar", 2));
  store.AddViews(mug, {SyntheticView(9, 90)});
  store.Rename(jar, "pot");
  store.Rename(jar, "pot");                                           // no change: not logged
  EXPECT_THROW(store.Enroll(SyntheticObject("mug", 2)), StoreError);  // refused: not logged
  store.Delete(mug);

  const std::vector<ModelChange> changes = store.ChangesAfter(0);
  using K = ModelChangeKind;
  EXPECT_THAT(Kinds(changes), ElementsAre(std::pair(mug, K::kEnroll), std::pair(jar, K::kEnroll),
                                          std::pair(mug, K::kAddViews), std::pair(jar, K::kRename),
                                          std::pair(mug, K::kDelete)));
  for (std::size_t i = 1; i < changes.size(); ++i) {
    EXPECT_LT(changes[i - 1].seq, changes[i].seq);
    EXPECT_LE(changes[i - 1].committed_at, changes[i].committed_at);
  }
  EXPECT_TRUE(std::regex_match(changes[0].committed_at,
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << changes[0].committed_at;
  // Paging: after the second change, two at a time.
  EXPECT_THAT(Kinds(store.ChangesAfter(changes[1].seq, 2)),
              ElementsAre(std::pair(mug, K::kAddViews), std::pair(jar, K::kRename)));
  EXPECT_TRUE(store.ChangesAfter(changes.back().seq).empty());
  EXPECT_EQ(store.LatestChangeSeq(), changes.back().seq);
  EXPECT_THROW(store.ChangesAfter(0, 0), std::invalid_argument);
}

// Each write notifies orbit_model_changes with its seq, once committed.
TEST(PostgresModelStoreTest, EachWriteNotifiesListenersWithItsSeqWhenCommitted) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  PGconn* listener = PQconnectdb(database.conninfo().c_str());
  ASSERT_EQ(PQstatus(listener), CONNECTION_OK) << PQerrorMessage(listener);
  PQclear(PQexec(listener, (std::string("LISTEN ") + kModelChangesChannel).c_str()));

  const ObjectId id = store.Enroll(SyntheticObject("mug", 3));
  store.Rename(id, "cup");

  std::vector<std::string> payloads;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (payloads.size() < 2 && std::chrono::steady_clock::now() < deadline) {
    pollfd socket{.fd = PQsocket(listener), .events = POLLIN, .revents = 0};
    ::poll(&socket, 1, 100);
    PQconsumeInput(listener);
    while (PGnotify* notify = PQnotifies(listener)) {
      EXPECT_STREQ(notify->relname, kModelChangesChannel);
      payloads.emplace_back(notify->extra);
      PQfreemem(notify);
    }
  }
  PQfinish(listener);
  const std::vector<ModelChange> changes = store.ChangesAfter(0);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_THAT(payloads,
              ElementsAre(std::to_string(changes[0].seq), std::to_string(changes[1].seq)));
}

// Two replicas writing at once: every write is logged once, and seq order is commit order (ids
// are handed out under the same lock, so the enrollments' ids rise with their seqs).
TEST(PostgresModelStoreTest, TwoReplicasWritingAtOnceLogEveryWriteInCommitOrder) {
  TestDatabase database;
  PostgresModelStore first(database.conninfo());
  PostgresModelStore second(database.conninfo());
  constexpr int kEach = 25;
  auto enroll = [](PostgresModelStore& store, const std::string& prefix) {
    for (int i = 0; i < kEach; ++i) store.Enroll(SyntheticObject(prefix + std::to_string(i), 4, i));
  };
  std::thread a(enroll, std::ref(first), "a");
  std::thread b(enroll, std::ref(second), "b");
  a.join();
  b.join();

  const std::vector<ModelChange> changes = second.ChangesAfter(0);
  ASSERT_EQ(changes.size(), 2u * kEach);
  std::set<ObjectId> objects;
  for (std::size_t i = 0; i < changes.size(); ++i) {
    EXPECT_EQ(changes[i].kind, ModelChangeKind::kEnroll);
    objects.insert(changes[i].object_id);
    if (i > 0) {
      EXPECT_LT(changes[i - 1].object_id, changes[i].object_id) << "change " << i;
    }
  }
  EXPECT_EQ(objects.size(), 2u * kEach);
  EXPECT_EQ(first.LoadAll().size(), 2u * kEach);
}

// Another process holding the write lock (another replica mid-write): writes wait up to the
// busy timeout and then fail clearly; reads carry on meanwhile.
TEST(PostgresModelStoreTest, AWriterWaitsForAnotherThenIsRefusedAsBusyWhileReadsGoOn) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo(), {.busy_timeout = std::chrono::milliseconds(200)});
  store.Enroll(SyntheticObject("mug", 2));
  PostgresConnection other(database.conninfo(), 0);
  other.Execute("BEGIN");
  other.Execute("SELECT pg_advisory_xact_lock(" + std::to_string(kPostgresWriteLockKey) + ")");

  const auto [code, message] = StoreErrorOf([&] { store.Enroll(SyntheticObject("jar", 2)); });
  EXPECT_EQ(code, StoreError::Code::kBusy);
  EXPECT_THAT(message, HasSubstr("another writer held the model store"));
  EXPECT_EQ(store.LoadAll().size(), 1u);
  EXPECT_EQ(store.List({}).size(), 1u);

  other.Execute("COMMIT");
  store.Enroll(SyntheticObject("jar", 2));
  EXPECT_EQ(store.LoadAll().size(), 2u);
}

// Reads see only committed objects, never another session's open write.
TEST(PostgresModelStoreTest, ReadersSeeOnlyCommittedObjects) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  store.Enroll(SyntheticObject("a", 3));
  PostgresConnection writer(database.conninfo(), 0);
  writer.Execute(
      "BEGIN;"
      "INSERT INTO objects (name, variant, created_at, updated_at) "
      "  VALUES ('half', 'cedd-lire', now(), now());"
      "INSERT INTO views (object_id, azimuth, descriptor, typical_distance) "
      "  SELECT id, 0, decode(repeat('00', 144), 'hex'), 0 FROM objects WHERE name = 'half';");

  EXPECT_EQ(store.LoadAll().size(), 1u);
  EXPECT_EQ(store.List({}).size(), 1u);
  EXPECT_EQ(store.Find("half"), std::nullopt);

  writer.Execute("COMMIT");
  const std::vector<ObjectModel> after = store.LoadAll();
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[1].name, "half");
  EXPECT_EQ(after[1].views.size(), 1u);
}

// The database itself fails the 37th view of a 72-view enrollment (as a full disk would, half-way
// through the write): nothing of it is stored or logged, and the store carries on.
TEST(PostgresModelStoreTest, AnEnrollmentThatFailsHalfWayLeavesNoTrace) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  store.Enroll(SyntheticObject("before", 10));
  database.Execute(R"sql(
    CREATE FUNCTION fail_at_view_37() RETURNS trigger LANGUAGE plpgsql AS $$
    BEGIN
      IF (SELECT count(*) FROM views WHERE object_id = NEW.object_id) = 36 THEN
        RAISE EXCEPTION 'injected failure at view 37' USING ERRCODE = 'check_violation';
      END IF;
      RETURN NEW;
    END $$;
    CREATE TRIGGER fail_at_view_37 BEFORE INSERT ON views
      FOR EACH ROW EXECUTE FUNCTION fail_at_view_37();
  )sql");

  const auto [code, message] = StoreErrorOf([&] { store.Enroll(SyntheticObject("mug", 72)); });
  EXPECT_EQ(code, StoreError::Code::kConstraint);
  EXPECT_THAT(message, HasSubstr("injected failure at view 37"));

  EXPECT_EQ(database.Int("SELECT count(*) FROM objects"), 1);
  EXPECT_EQ(database.Int("SELECT count(*) FROM views"), 10);
  EXPECT_EQ(database.Int("SELECT count(*) FROM model_changes"), 1);
  EXPECT_EQ(store.Find("mug"), std::nullopt);
  database.Execute("DROP TRIGGER fail_at_view_37 ON views");
  const ObjectId id = store.Enroll(SyntheticObject("mug", 72));
  EXPECT_EQ(store.Get(id)->views.size(), 72u);
}

// The server ends the store's idle connections (a restart, an administrator): the next calls
// connect afresh instead of failing on a dead connection.
TEST(PostgresModelStoreTest, ConnectionsTheServerClosedWhileIdleAreReplaced) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  for (int i = 0; i < 3; ++i) store.Enroll(SyntheticObject("o" + std::to_string(i), 2));

  EXPECT_GE(database.Int("SELECT count(pg_terminate_backend(pid, 5000)) FROM pg_stat_activity "
                         "WHERE datname = current_database() AND pid <> pg_backend_pid()"),
            1);

  EXPECT_EQ(store.LoadAll().size(), 3u);
  store.Enroll(SyntheticObject("after", 2));
  EXPECT_EQ(store.List({}).size(), 4u);
}

TEST(PostgresModelStoreTest, AnUnreachableServerIsAClearErrorThatHidesThePassword) {
  testing::ScratchDir dir;  // an empty folder: no server's socket in it
  const std::string uri =
      "postgresql://orbit:s3cret@/models?host=" + dir.path().string() + "&connect_timeout=5";
  const auto [code, message] = StoreErrorOf([&] { PostgresModelStore store(uri); });
  EXPECT_EQ(code, StoreError::Code::kIo);
  EXPECT_THAT(message, HasSubstr("cannot connect to PostgreSQL"));
  EXPECT_THAT(message, HasSubstr("host=" + dir.path().string()));
  EXPECT_THAT(message, HasSubstr("dbname=models"));
  EXPECT_THAT(message, HasSubstr("No such file or directory"));  // libpq's reason
  EXPECT_THAT(message, Not(HasSubstr("s3cret")));
}

TEST(PostgresModelStoreTest, ARefusedConnectionCarriesTheServersReason) {
  const std::string conninfo =
      testing::PostgresTestCluster::Shared().ConnectionString("no_such_database") +
      " password=s3cret";
  const auto [code, message] = StoreErrorOf([&] { PostgresModelStore store(conninfo); });
  EXPECT_EQ(code, StoreError::Code::kIo);
  EXPECT_THAT(message, HasSubstr("database \"no_such_database\" does not exist"));
  EXPECT_THAT(message, HasSubstr("dbname=no_such_database"));
  EXPECT_THAT(message, Not(HasSubstr("s3cret")));
  EXPECT_THROW(PostgresModelStore("postgresql://[bad"), std::invalid_argument);
}

// A backup of the PostgreSQL store is one private SQLite store file holding the same objects
// under the same ids, and never handing out the id of an object deleted before it was taken.
TEST(PostgresModelStoreTest, ABackupIsAPrivateSqliteStoreOfTheSameObjects) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  const ObjectId mug = store.Enroll(SyntheticObject("mug", 3));
  store.Delete(store.Enroll(SyntheticObject("jar", 2, 5)));
  testing::ScratchDir dir;
  const testing::ScopedUmask everyone_reads(022);
  store.Backup(dir / "orbit.db");

  EXPECT_EQ(testing::FileMode(dir / "orbit.db"), 0600u);
  EXPECT_FALSE(std::filesystem::exists(dir / "orbit.db.partial"));
  EXPECT_EQ(testing::RawDatabase(dir / "orbit.db").Text("PRAGMA journal_mode"), "delete");
  SqliteModelStore copy(dir / "orbit.db");
  EXPECT_EQ(copy.Get(mug), store.Get(mug));
  EXPECT_EQ(copy.List({}).size(), 1u);
  EXPECT_EQ(copy.Enroll(SyntheticObject("pot", 2, 9)), 3);  // not jar's 2
}

// The seq of each change, in the order given.
std::vector<std::int64_t> Seqs(const std::vector<ModelChange>& changes) {
  std::vector<std::int64_t> seqs;
  for (const ModelChange& change : changes) seqs.push_back(change.seq);
  return seqs;
}

TEST(PostgresModelStoreTest, TheLogIsPrunedThroughWhatEveryLiveReplicaHasApplied) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  for (int i = 0; i < 5; ++i) store.Enroll(SyntheticObject("o" + std::to_string(i), 2, i));
  const std::chrono::minutes lease(5);
  EXPECT_EQ(store.PruneChanges(lease), 0);  // no replica has said what it applied: all kept
  EXPECT_EQ(database.Int("SELECT count(*) FROM model_changes"), 5);

  store.ReportApplied("a", 3);
  store.ReportApplied("b", 5);
  EXPECT_EQ(store.PruneChanges(lease), 3);
  EXPECT_THAT(Seqs(store.ChangesAfter(3)), ElementsAre(4, 5));
  EXPECT_EQ(database.Int("SELECT count(*) FROM model_changes"), 2);

  // "a" has been silent for longer than the lease: it is not waited for, and is forgotten.
  database.Execute(
      "UPDATE replica_progress SET reported_at = now() - interval '10 minutes' "
      "WHERE replica = 'a'");
  EXPECT_EQ(store.PruneChanges(lease), 5);
  EXPECT_EQ(database.Int("SELECT count(*) FROM model_changes"), 0);
  EXPECT_EQ(database.Text("SELECT string_agg(replica, ',') FROM replica_progress"), "b");
  EXPECT_EQ(store.LatestChangeSeq(), 5);  // the log is empty; its position is not lost

  store.Enroll(SyntheticObject("o5", 2, 5));
  EXPECT_THAT(Seqs(store.ChangesAfter(5)), ElementsAre(6));
}

TEST(PostgresModelStoreTest, ChangesThatWerePrunedAreRefusedNotSkipped) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  for (int i = 0; i < 3; ++i) store.Enroll(SyntheticObject("o" + std::to_string(i), 2, i));
  store.ReportApplied("a", 2);
  ASSERT_EQ(store.PruneChanges(std::chrono::minutes(5)), 2);

  try {
    store.ChangesAfter(1);
    ADD_FAILURE() << "answered without change 2, which was pruned";
  } catch (const ChangeLogPruned& e) {
    EXPECT_EQ(e.after_seq(), 1);
    EXPECT_EQ(e.pruned_through(), 2);
    EXPECT_STREQ(e.what(), "the change log was pruned past change 1 (through 2)");
  }
  EXPECT_THROW(store.ChangesAfter(0), ChangeLogPruned);
  EXPECT_THAT(Seqs(store.ChangesAfter(2)), ElementsAre(3));
}

}  // namespace
}  // namespace orbit
