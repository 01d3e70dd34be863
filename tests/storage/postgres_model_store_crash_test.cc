// Crashes around the PostgreSQL store. kill -9 of a process in the middle of enrolling: the server
// rolls the dead session's transaction back, so every object left is whole and logged once, and
// every enrollment acknowledged before the kill is there. A crash of the database server: every
// acknowledged write is there after its restart.
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/postgres_model_store.h"
#include "tests/support/child_process.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using testing::Acknowledged;
using testing::Child;
using testing::SyntheticObject;
using testing::TestDatabase;

// Large transactions (1024 views with 16 KB thumbnails: 16 MB each) make the kill land inside a
// write in progress rather than between two.
TEST(PostgresStoreCrashTest, KillingAWriterMidEnrollmentLeavesOnlyWholeLoggedObjects) {
  TestDatabase database;
  { PostgresModelStore create(database.conninfo()); }
  const std::string conninfo = database.conninfo();
  auto write_forever = [&] {
    PostgresModelStore store(conninfo);
    for (int i = 0;; ++i) {
      Enrollment big = SyntheticObject("big" + std::to_string(i), 1024, i);
      big.thumbnails.assign(1024, std::string(16 * 1024, static_cast<char>('a' + i % 26)));
      store.Enroll(big);
      std::printf("enrolled big%d\n", i);
      std::fflush(stdout);
    }
    return 0;
  };

  std::vector<std::string> lines;
  {
    Child child(write_forever);
    lines.push_back(child.ReadLine());
    ASSERT_EQ(lines.back(), "enrolled big0");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_TRUE(child.Kill(lines));
  }

  const std::set<std::string> acknowledged = Acknowledged(lines);
  PostgresModelStore store(database.conninfo());
  std::set<std::string> present;
  for (const ObjectModel& model : store.LoadAll()) {
    EXPECT_EQ(model.views.size(), 1024u) << model.name;
    present.insert(model.name);
  }
  for (const std::string& name : acknowledged) {
    EXPECT_TRUE(present.count(name)) << name << " was acknowledged, then lost";
  }
  // At most one object committed without its line printed yet.
  EXPECT_LE(present.size(), acknowledged.size() + 1);
  EXPECT_EQ(database.Int("SELECT count(*) FROM views WHERE thumbnail IS NULL"), 0);
  // Logged exactly when stored: one enroll change per object present, none for the rolled back.
  const std::vector<ModelChange> changes = store.ChangesAfter(0);
  EXPECT_EQ(changes.size(), present.size());
  for (const ModelChange& change : changes) {
    EXPECT_EQ(change.kind, ModelChangeKind::kEnroll);
    EXPECT_TRUE(store.Get(change.object_id).has_value()) << change.object_id;
  }
}

// The database server itself crashes (pg_ctl stop --mode immediate: no shutdown checkpoint,
// the restart replays the write-ahead log) right after the store acknowledged two writes: both
// are there after the restart, and the same store carries on with fresh connections. On a
// private server: the shared one serves other tests meanwhile.
TEST(PostgresStoreCrashTest, AcknowledgedWritesSurviveACrashOfTheDatabaseServer) {
  const testing::PrivatePostgresServer server;
  PostgresModelStore store(server.conninfo());
  const ObjectId id = store.Enroll(SyntheticObject("mug", 72));
  store.Rename(id, "cup");

  server.Crash();
  server.Restart();

  const std::optional<ObjectSummary> cup = store.Find("cup");
  ASSERT_TRUE(cup.has_value());
  EXPECT_EQ(cup->id, id);
  EXPECT_EQ(cup->view_count, 72);
  EXPECT_EQ(store.ChangesAfter(0).size(), 2u);
  EXPECT_GT(store.Enroll(SyntheticObject("jar", 2)), id);
}

}  // namespace
}  // namespace orbit
