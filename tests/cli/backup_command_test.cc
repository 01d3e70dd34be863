// orbit backup (cli/backup_command.cc) as an operator runs it: what --to may replace.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_files.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::SyntheticObject;

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

}  // namespace
}  // namespace orbit
