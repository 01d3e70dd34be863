// Reads beside writes, and backups while writing: readers never wait for a writer and only ever
// see whole, committed objects (docs/design.md#overview: enrollment, listing and deleting
// while queries run).
#include <atomic>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::RawDatabase;
using testing::ScratchDir;
using testing::SyntheticObject;

constexpr int kViews = 72;

// Fails the test unless every object has exactly kViews views and ids strictly increase.
void ExpectWholeObjects(const std::vector<ObjectModel>& models) {
  for (std::size_t i = 0; i < models.size(); ++i) {
    EXPECT_EQ(models[i].views.size(), static_cast<std::size_t>(kViews)) << models[i].name;
    if (i > 0) {
      EXPECT_LT(models[i - 1].id, models[i].id);
    }
  }
}

TEST(StoreConcurrencyTest, ReadersDoNotWaitForAnOpenWriteAndSeeOnlyCommittedObjects) {
  ScratchDir dir;
  // A reader that had to wait for the writer would fail after 100 ms with kBusy.
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true,
                                             .busy_timeout = std::chrono::milliseconds(100)});
  store.Enroll(SyntheticObject("a", 3));
  store.Enroll(SyntheticObject("b", 3));
  RawDatabase writer(dir / "models.db");
  writer.Execute(
      "BEGIN IMMEDIATE;"
      "INSERT INTO objects (name, variant, created_at, updated_at) "
      "  VALUES ('half', 'cedd-lire', 'now', 'now');"
      "INSERT INTO views (object_id, azimuth, descriptor, typical_distance) "
      "  SELECT last_insert_rowid(), 0, zeroblob(144), 0;");

  EXPECT_EQ(store.LoadAll().size(), 2u);
  EXPECT_EQ(store.List({}).size(), 2u);
  EXPECT_EQ(store.Find("half"), std::nullopt);
  EXPECT_FALSE(store.Get(3).has_value());

  writer.Execute("COMMIT");
  const std::vector<ObjectModel> after = store.LoadAll();
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[2].name, "half");
  EXPECT_EQ(after[2].views.size(), 1u);
}

TEST(StoreBackupTest, ABackupTakenWhileWritingIsAConsistentStore) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  for (int i = 0; i < 5; ++i) store.Enroll(SyntheticObject("first" + std::to_string(i), kViews, i));
  std::atomic<bool> writing = true;
  std::atomic<int> enrolled = 5;
  std::thread writer([&] {
    for (int i = 0; writing; ++i) {
      store.Enroll(SyntheticObject("obj" + std::to_string(i), kViews, i));
      ++enrolled;
      if (i % 3 == 0) {
        store.Delete(store.Find("obj" + std::to_string(i))->id);
        --enrolled;
      }
    }
  });

  for (int round = 0; round < 3; ++round) store.Backup(dir / "backup.db");  // replaces each time
  const int after_backup = enrolled;
  writing = false;
  writer.join();

  EXPECT_FALSE(std::filesystem::exists(dir / "backup.db.partial"));
  {
    RawDatabase raw(dir / "backup.db");
    EXPECT_EQ(raw.Text("PRAGMA integrity_check"), "ok");
    EXPECT_EQ(raw.Text("PRAGMA journal_mode"), "delete");  // one self-contained file
    EXPECT_EQ(raw.Int("SELECT count(*) FROM views WHERE object_id NOT IN (SELECT id FROM objects)"),
              0);
  }
  SqliteModelStore copy(dir / "backup.db");
  const std::vector<ObjectModel> models = copy.LoadAll();
  ExpectWholeObjects(models);
  EXPECT_GE(models.size(), 5u);
  // `enrolled` trails the store by at most the one write in flight.
  EXPECT_LE(models.size(), static_cast<std::size_t>(after_backup) + 1);
  EXPECT_EQ(models[0].name, "first0");
}

TEST(StoreBackupTest, RefusesToOverwriteTheStoreAndReportsAnUnwritableDestination) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("mug", 3));

  EXPECT_THROW(store.Backup(dir / "models.db"), std::invalid_argument);
  EXPECT_THROW(store.Backup(dir / "." / "models.db"), std::invalid_argument);
  try {
    store.Backup(dir / "no" / "such" / "folder" / "backup.db");
    ADD_FAILURE() << "backed up into a missing folder";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.code(), StoreError::Code::kIo);
    EXPECT_THAT(e.what(), HasSubstr("cannot back up"));
    EXPECT_THAT(e.what(), HasSubstr("No such file or directory"));
  }
  EXPECT_EQ(store.LoadAll().size(), 1u);
}

}  // namespace
}  // namespace orbit
