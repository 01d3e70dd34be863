// What only the SQLite store does; the contracts it shares with every ModelStore (what goes in
// comes out, ids, names, paging, deletes, reopening) are tested on both stores in
// tests/storage/model_store_test.cc.
#include "storage/sqlite_model_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using testing::FileMode;
using ::testing::HasSubstr;
using testing::ScopedUmask;
using testing::ScratchDir;
using testing::StoreErrorOf;
using testing::SyntheticObject;

TEST(SqliteModelStoreTest, OpeningAMissingFileWithoutCreateIsAClearError) {
  ScratchDir dir;
  const auto [code, message] = StoreErrorOf([&] { SqliteModelStore store(dir / "absent.db"); });
  EXPECT_EQ(code, StoreError::Code::kIo);
  EXPECT_THAT(message, HasSubstr("absent.db does not exist"));
  EXPECT_FALSE(std::filesystem::exists(dir / "absent.db"));
}

// Under the umask most shells have (files readable by everyone), a new store, its write-ahead
// log and its shared-memory file are still its owner's alone: they hold the operator's objects.
TEST(SqliteModelStoreTest, ANewStoreAndItsLogFilesAreReadableByTheirOwnerOnly) {
  ScratchDir dir;
  const ScopedUmask everyone_reads(022);
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("mug", 2));
  ASSERT_TRUE(std::filesystem::exists(dir / "models.db-wal"));
  ASSERT_TRUE(std::filesystem::exists(dir / "models.db-shm"));
  EXPECT_EQ(FileMode(dir / "models.db"), 0600u);
  EXPECT_EQ(FileMode(dir / "models.db-wal"), 0600u);
  EXPECT_EQ(FileMode(dir / "models.db-shm"), 0600u);
}

// A backup is as private as its store, and no more: a store its group may read gives a copy its
// group may read, whatever the umask.
TEST(SqliteModelStoreTest, ABackupHasItsStoresMode) {
  ScratchDir dir;
  const ScopedUmask everyone_reads(022);
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("mug", 2));
  store.Backup(dir / "backup.db");
  EXPECT_EQ(FileMode(dir / "backup.db"), 0600u);

  std::filesystem::permissions(dir / "models.db", std::filesystem::perms(0640));
  store.Backup(dir / "backup.db");  // replaces the copy, mode and all
  EXPECT_EQ(FileMode(dir / "backup.db"), 0640u);
}

}  // namespace
}  // namespace orbit
