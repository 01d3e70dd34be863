// CreateStoreFile and HoldsOnlyAStore (storage/store_files.h) on real files.
#include "storage/store_files.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using testing::FileMode;
using ::testing::HasSubstr;
using testing::RawDatabase;
using testing::ScopedUmask;
using testing::ScratchDir;
using testing::StoreErrorOf;
using testing::SyntheticObject;
namespace fs = std::filesystem;

TEST(StoreFilesTest, ACreatedFileHasExactlyTheModeAskedForWhateverTheUmask) {
  ScratchDir dir;
  {
    const ScopedUmask everyone_reads(022);
    EXPECT_TRUE(CreateStoreFile(dir / "private.db", kStoreFileMode));
  }
  {
    const ScopedUmask nobody_else(077);
    // A backup of a store its group may read keeps that, though the umask would take it away.
    EXPECT_TRUE(CreateStoreFile(dir / "group.db", fs::perms(0640)));
  }
  EXPECT_EQ(FileMode(dir / "private.db"), 0600u);
  EXPECT_EQ(FileMode(dir / "group.db"), 0640u);
  EXPECT_EQ(fs::file_size(dir / "private.db"), 0u);
}

TEST(StoreFilesTest, AnExistingFileIsLeftAsItIs) {
  ScratchDir dir;
  const fs::path notes = dir.Write("notes.txt", "keep me");
  fs::permissions(notes, fs::perms(0644));
  EXPECT_FALSE(CreateStoreFile(notes, kStoreFileMode));
  EXPECT_EQ(FileMode(notes), 0644u);
  EXPECT_EQ(fs::file_size(notes), 7u);
}

TEST(StoreFilesTest, AFileThatCannotBeCreatedIsAnIoErrorNamingIt) {
  ScratchDir dir;
  const auto [code, message] =
      StoreErrorOf([&] { CreateStoreFile(dir / "no" / "folder" / "x.db", kStoreFileMode); });
  EXPECT_EQ(code, StoreError::Code::kIo);
  EXPECT_THAT(message, HasSubstr("cannot create " + (dir / "no" / "folder" / "x.db").string()));
  EXPECT_THAT(message, HasSubstr("No such file or directory"));
}

TEST(StoreFilesTest, OnlyAStoreOrAnEmptyFileMayBeReplacedByACopy) {
  ScratchDir dir;
  {
    SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
    store.Enroll(SyntheticObject("mug", 2));
    store.Backup(dir / "backup.db");
  }
  EXPECT_TRUE(HoldsOnlyAStore(dir / "models.db"));
  EXPECT_TRUE(HoldsOnlyAStore(dir / "backup.db"));
  EXPECT_TRUE(HoldsOnlyAStore(dir.Write("empty", "")));

  EXPECT_FALSE(HoldsOnlyAStore(dir.Write("thesis.txt", "four years of work")));
  RawDatabase(dir / "accounts.db").Execute("CREATE TABLE accounts (name TEXT)");
  EXPECT_FALSE(HoldsOnlyAStore(dir / "accounts.db"));
  fs::create_directory(dir / "folder");
  EXPECT_FALSE(HoldsOnlyAStore(dir / "folder"));
  EXPECT_FALSE(HoldsOnlyAStore(dir / "missing.db"));
}

}  // namespace
}  // namespace orbit
