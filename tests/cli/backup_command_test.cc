// orbit backup (cli/backup_command.cc) as an operator runs it: what --to may replace, and a
// PostgreSQL store copied while a replica writes, restored (cli/restore_command.cc) into both
// kinds of store.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/postgres_model_store.h"
#include "storage/sqlite_model_store.h"
#include "storage/store_files.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/wait_until.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::SyntheticObject;
using testing::TestDatabase;

// A store with one object, "mug", in `dir`/models.db; returns its path.
std::string StoreWithAMug(const ScratchDir& dir) {
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("mug", 2));
  return (dir / "models.db").string();
}

TEST(BackupCommandTest, AFileThatIsNotAStoreIsKeptUnlessForced) {
  ScratchDir dir;
  const std::string db = StoreWithAMug(dir);
  const std::filesystem::path report = dir.Write("report.txt", "the quarterly report");

  const testing::CommandResult refused = RunOrbit("backup --db " + db + " --to " + report.string());
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(refused.err, "orbit backup: --to " + report.string() +
                             " exists and is not an Orbit model store; pass --force to replace "
                             "it\n");
  EXPECT_EQ(std::filesystem::file_size(report), std::string("the quarterly report").size());
  EXPECT_FALSE(HoldsOnlyAStore(report));  // still the report, not a copy of the store

  const testing::CommandResult forced =
      RunOrbit("backup --db " + db + " --to " + report.string() + " --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(SqliteModelStore(report).Find("mug").has_value());
}

TEST(BackupCommandTest, AnEarlierBackupIsReplacedWithoutForce) {
  ScratchDir dir;
  const std::string db = StoreWithAMug(dir);
  const std::string backup = (dir / "backup.db").string();
  ASSERT_EQ(RunOrbit("backup --db " + db + " --to " + backup).exit_code, 0);
  SqliteModelStore(db).Enroll(SyntheticObject("jar", 2, 7));

  const testing::CommandResult again = RunOrbit("backup --db " + db + " --to " + backup);
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.out, HasSubstr("backed up " + db + " to " + backup));
  EXPECT_TRUE(SqliteModelStore(backup).Find("jar").has_value());
}

// The objects of a store, by name, with their view counts.
std::map<std::string, std::int64_t> ViewCounts(ModelStore& store) {
  std::map<std::string, std::int64_t> counts;
  for (const ObjectSummary& object : store.List({.after_id = 0, .limit = kMaxListLimit})) {
    counts[object.name] = object.view_count;
  }
  return counts;
}

// Every object as ForEachObject hands them over.
std::vector<StoredObject> EveryObject(ModelStore& store) {
  std::vector<StoredObject> objects;
  store.ForEachObject([&](const StoredObject& object) { objects.push_back(object); });
  return objects;
}

// A replica enrolls and deletes without pause while `orbit backup --store` copies the database:
// the backup is the store as it was after some number of those writes, each write whole or
// absent; it restores into an empty PostgreSQL database and into a new SQLite file unchanged.
TEST(PostgresBackupCommandTest, ABackupTakenWhileAReplicaWritesRestoresOneMomentWhole) {
  TestDatabase database;
  PostgresModelStore replica(database.conninfo());
  for (int i = 0; i < 40; ++i) replica.Enroll(SyntheticObject("seed" + std::to_string(i), 24, i));

  std::mutex mutex;
  // states[k]: the store after the writer's first k writes.
  std::vector<std::map<std::string, std::int64_t>> states = {ViewCounts(replica)};
  const auto written = [&] {
    std::lock_guard lock(mutex);
    return states.size();
  };
  std::atomic<bool> writing = true;
  std::thread writer([&] {
    std::map<std::string, std::int64_t> now = states.front();
    for (int i = 0; writing; ++i) {
      const std::string name = "w" + std::to_string(i);
      replica.Enroll(SyntheticObject(name, 8, 100 + i));
      now[name] = 8;
      std::string gone;
      if (i % 2 == 1) {
        gone = "w" + std::to_string(i - 1);
        replica.Delete(replica.Find(gone)->id);
      }
      std::lock_guard lock(mutex);
      states.push_back(now);
      if (!gone.empty()) {
        now.erase(gone);
        states.push_back(now);
      }
    }
  });
  ASSERT_TRUE(testing::WaitUntil([&] { return written() > 5; }));
  const std::size_t before = written();
  ScratchDir dir;
  const std::string backup = (dir / "orbit.db").string();
  const testing::CommandResult backed_up =
      RunOrbit("backup --store '" + database.conninfo() + "' --to " + backup);
  const std::size_t after = written();
  writing = false;
  writer.join();
  ASSERT_EQ(backed_up.exit_code, 0) << backed_up.err;
  EXPECT_THAT(backed_up.out, HasSubstr(" to " + backup));
  ASSERT_GT(after, before) << "no write landed during the backup";

  SqliteModelStore copy(backup);
  const std::map<std::string, std::int64_t> backed = ViewCounts(copy);
  bool one_moment = false;
  for (std::size_t k = before - 1; k < states.size(); ++k) one_moment |= states[k] == backed;
  EXPECT_TRUE(one_moment) << "the backup's " << backed.size()
                          << " objects are the store at no moment of the writes";
  const std::vector<StoredObject> objects = EveryObject(copy);

  TestDatabase empty;
  const testing::CommandResult into_postgres =
      RunOrbit("restore --from " + backup + " --store '" + empty.conninfo() + "'");
  ASSERT_EQ(into_postgres.exit_code, 0) << into_postgres.err;
  EXPECT_THAT(into_postgres.out, HasSubstr("(" + std::to_string(objects.size()) + " objects)"));
  PostgresModelStore restored(empty.conninfo());
  EXPECT_EQ(EveryObject(restored), objects);

  const std::string file = (dir / "restored.db").string();
  const testing::CommandResult into_sqlite = RunOrbit("restore --from " + backup + " --db " + file);
  ASSERT_EQ(into_sqlite.exit_code, 0) << into_sqlite.err;
  SqliteModelStore restored_file(file);
  EXPECT_EQ(EveryObject(restored_file), objects);
}

}  // namespace
}  // namespace orbit
