// orbit restore (cli/restore_command.cc) as an operator runs it: into a new SQLite file, and
// the refusals. Into PostgreSQL, under writes: tests/cli/backup_command_test.cc.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using testing::FileMode;
using ::testing::HasSubstr;
using testing::RunOrbit;
using testing::ScopedUmask;
using testing::ScratchDir;
using testing::SyntheticObject;

TEST(RestoreCommandTest, ABackupRestoresIntoANewPrivateFileUnderItsIds) {
  ScratchDir dir;
  {
    SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
    store.Enroll(SyntheticObject("mug", 3));
    store.Delete(store.Enroll(SyntheticObject("jar", 2, 5)));
    store.Enroll(SyntheticObject("pot", 2, 9));
    store.Backup(dir / "backup.db");
  }
  const ScopedUmask everyone_reads(022);
  const std::string restored = (dir / "restored.db").string();
  const testing::CommandResult result =
      RunOrbit("restore --from " + (dir / "backup.db").string() + " --db " + restored);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out,
            "restored " + (dir / "backup.db").string() + " into " + restored + " (2 objects)\n");
  EXPECT_EQ(FileMode(restored), 0600u);
  SqliteModelStore store(restored);
  EXPECT_EQ(store.Find("pot")->id, 3);
  EXPECT_EQ(store.Enroll(SyntheticObject("bowl", 2, 20)), 4);
}

TEST(RestoreCommandTest, AStoreThatHoldsObjectsIsRefusedAndKeptAsItWas) {
  ScratchDir dir;
  SqliteModelStore(dir / "backup.db", {.create_if_missing = true})
      .Enroll(SyntheticObject("mug", 2));
  const std::string target = (dir / "models.db").string();
  SqliteModelStore(target, {.create_if_missing = true}).Enroll(SyntheticObject("jar", 2, 5));

  const testing::CommandResult result =
      RunOrbit("restore --from " + (dir / "backup.db").string() + " --db " + target);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "orbit: " + target + " holds 1 objects: restore into an empty store\n");
  SqliteModelStore store(target);
  EXPECT_TRUE(store.Find("jar").has_value());
  EXPECT_FALSE(store.Find("mug").has_value());
}

TEST(RestoreCommandTest, AMissingBackupOrStoreIsAClearError) {
  ScratchDir dir;
  const testing::CommandResult missing = RunOrbit("restore --from " + (dir / "absent.db").string() +
                                                  " --db " + (dir / "models.db").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, HasSubstr((dir / "absent.db").string() + " does not exist"));
  EXPECT_FALSE(std::filesystem::exists(dir / "models.db"));

  SqliteModelStore(dir / "backup.db", {.create_if_missing = true});
  const testing::CommandResult neither = RunOrbit("restore --from " + (dir / "backup.db").string());
  EXPECT_EQ(neither.exit_code, 2);
  EXPECT_THAT(neither.err, HasSubstr("give the model store: --db FILE (SQLite) or --store"));
}

}  // namespace
}  // namespace orbit
