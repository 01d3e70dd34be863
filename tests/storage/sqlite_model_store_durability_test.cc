// Writes are all or nothing, another writer is waited for (then refused, clearly), and the
// write-ahead log stays bounded (docs/design.md#service-behaviour: enrollment is atomic and
// durable).
#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

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
using testing::SyntheticView;

// Makes the database itself fail the 37th view of any object, half-way through a 72-view write:
// a real SQLite error raised mid-transaction, as a full disk or an I/O error would be.
constexpr const char* kFailAtView37 = R"sql(
  CREATE TRIGGER fail_at_view_37 BEFORE INSERT ON views
  WHEN (SELECT count(*) FROM views WHERE object_id = NEW.object_id) = 36
  BEGIN SELECT RAISE(ABORT, 'injected failure at view 37'); END;
)sql";

TEST(StoreAtomicityTest, AnEnrollmentThatFailsHalfWayLeavesNoTrace) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("before", 10));
  RawDatabase raw(dir / "models.db");
  raw.Execute(kFailAtView37);

  try {
    store.Enroll(SyntheticObject("mug", 72));
    ADD_FAILURE() << "the enrollment succeeded";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.code(), StoreError::Code::kConstraint);
    EXPECT_THAT(e.what(), HasSubstr("injected failure at view 37"));
  }

  EXPECT_EQ(raw.Int("SELECT count(*) FROM objects"), 1);
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views"), 10);
  EXPECT_EQ(store.Find("mug"), std::nullopt);
  EXPECT_EQ(store.LoadAll().size(), 1u);
  // The store carries on: the name is free, and the id sequence was rolled back too.
  raw.Execute("DROP TRIGGER fail_at_view_37");
  EXPECT_EQ(store.Enroll(SyntheticObject("mug", 72)), 2);
  EXPECT_EQ(store.Get(2)->views.size(), 72u);
}

TEST(StoreAtomicityTest, AddingViewsThatFailsHalfWayLeavesTheObjectAsItWas) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  const ObjectId id = store.Enroll(SyntheticObject("mug", 30));
  const StoredObject before = *store.Get(id);
  RawDatabase raw(dir / "models.db");
  raw.Execute(kFailAtView37);

  // Views 31..36 would fit; the 37th fails.
  EXPECT_THROW(store.AddViews(id, SyntheticObject("more", 10, 100).views), StoreError);

  const StoredObject after = *store.Get(id);
  EXPECT_EQ(after.views.size(), 30u);
  EXPECT_EQ(after.summary.updated_at, before.summary.updated_at);
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views"), 30);
}

TEST(StoreWriterLockTest, AWriterWaitsForAnotherWriterThenCommits) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  RawDatabase other(dir / "models.db");  // another process's connection, as far as SQLite knows
  other.Execute("BEGIN IMMEDIATE");
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    other.Execute("COMMIT");
  });

  const ObjectId id = store.Enroll(SyntheticObject("mug", 5));  // waits, within 5 s, then writes

  release.join();
  EXPECT_EQ(store.Get(id)->views.size(), 5u);
}

TEST(StoreWriterLockTest, AWriterGivesUpAfterTheBusyTimeoutWithAClearError) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true,
                                             .busy_timeout = std::chrono::milliseconds(100)});
  RawDatabase other(dir / "models.db");
  other.Execute("BEGIN IMMEDIATE");

  try {
    store.Enroll(SyntheticObject("mug", 5));
    ADD_FAILURE() << "wrote while another writer held the lock";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.code(), StoreError::Code::kBusy);
    EXPECT_THAT(e.what(), HasSubstr("models.db is locked by another writer for longer than the "
                                    "busy timeout"));
  }
  other.Execute("COMMIT");
  EXPECT_EQ(store.Find("mug"), std::nullopt);
  store.Enroll(SyntheticObject("mug", 5));
  EXPECT_TRUE(store.Find("mug").has_value());
}

// The write-ahead log grows by every commit until a checkpoint copies it into the database and
// the next write recycles it. Readers pin the log while they read; the store must still keep it
// bounded.
TEST(StoreCheckpointTest, TheWriteAheadLogStaysBoundedUnderSteadyWritesAndReads) {
  ScratchDir dir;
  const std::filesystem::path file = dir / "models.db";
  SqliteModelStoreOptions options{.create_if_missing = true, .checkpoint_pages = 64};
  SqliteModelStore store(file, options);
  std::atomic<bool> writing = true;
  std::thread reader([&] {
    while (writing) store.LoadAll();
  });

  constexpr int kObjects = 120;
  std::uintmax_t largest_log = 0;
  for (int i = 0; i < kObjects; ++i) {
    Enrollment object = SyntheticObject("obj" + std::to_string(i), 72, i);
    object.thumbnails.assign(72, std::string(2048, static_cast<char>('a' + i % 26)));
    store.Enroll(object);  // about 160 KB a commit: 19 MB in all
    largest_log = std::max(largest_log, std::filesystem::file_size(file.string() + "-wal"));
  }
  writing = false;
  reader.join();

  // Escalation at 4 x 64 pages of 4 KiB (1 MiB) plus one commit; never the 19 MB written.
  EXPECT_LT(largest_log, 2u * 1024 * 1024);
  EXPECT_GT(std::filesystem::file_size(file), 15u * 1024 * 1024);  // the data did reach the file
  EXPECT_EQ(store.LoadAll().size(), static_cast<std::size_t>(kObjects));
}

}  // namespace
}  // namespace orbit
