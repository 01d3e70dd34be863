// orbit list, delete and backup (cli/list_command.cc, cli/delete_command.cc,
// cli/backup_command.cc) on real store files, as an operator runs them.

#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilDir;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using testing::OutputLines;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::UnindentedLines;

TEST(ListCommandTest, ImportListDeleteAndBackupCoil100) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();

  const testing::CommandResult imported =
      RunOrbit("import --db " + db + " --layout coil100 --data " + CoilDir() + " --objects 1-3");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_THAT(UnindentedLines(imported.out),
              ElementsAre("enrolled obj1 (id 1, 72 views)", "enrolled obj2 (id 2, 72 views)",
                          "enrolled obj3 (id 3, 72 views)"));
  EXPECT_THAT(imported.err, HasSubstr("3 objects enrolled, 0 already present"));

  const testing::CommandResult listed = RunOrbit("list --db " + db);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_THAT(OutputLines(listed.out),
              ElementsAre(MatchesRegex("1 obj1 cedd-soft-hsv-hog 72 [-0-9T:.]+Z"),
                          MatchesRegex("2 obj2 cedd-soft-hsv-hog 72 [-0-9T:.]+Z"),
                          MatchesRegex("3 obj3 cedd-soft-hsv-hog 72 [-0-9T:.]+Z")));

  const testing::CommandResult json = RunOrbit("list --db " + db + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const std::vector<std::string> json_lines = OutputLines(json.out);
  ASSERT_EQ(json_lines.size(), 3u);
  const nlohmann::json second = nlohmann::json::parse(json_lines[1]);
  EXPECT_EQ(second["id"], 2);
  EXPECT_EQ(second["name"], "obj2");
  EXPECT_EQ(second["variant"], "cedd-soft-hsv-hog");
  EXPECT_EQ(second["views"], 72);
  EXPECT_EQ(second["metadata"], nlohmann::json::object());

  const testing::CommandResult deleted = RunOrbit("delete --db " + db + " obj2");
  EXPECT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_EQ(deleted.out, "deleted obj2 (id 2, 72 views)\n");
  const testing::CommandResult again = RunOrbit("delete --db " + db + " obj2");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_EQ(again.err, "orbit delete: no object named \"obj2\" in " + db + "\n");

  const std::string backup = (dir / "backup.db").string();
  const testing::CommandResult backed_up = RunOrbit("backup --db " + db + " --to " + backup);
  EXPECT_EQ(backed_up.exit_code, 0) << backed_up.err;
  EXPECT_THAT(backed_up.out, HasSubstr("backed up " + db + " to " + backup));
  const testing::CommandResult from_backup = RunOrbit("list --db " + backup);
  EXPECT_EQ(from_backup.out, RunOrbit("list --db " + db).out);
  EXPECT_EQ(OutputLines(from_backup.out).size(), 2u);

  // Importing again enrolls only what is missing.
  const testing::CommandResult resumed =
      RunOrbit("import --db " + db + " --layout coil100 --data " + CoilDir() + " --objects 1-3");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(
      UnindentedLines(resumed.out),
      ElementsAre("skipped obj1 (already in the store as id 1)", "enrolled obj2 (id 4, 72 views)",
                  "skipped obj3 (already in the store as id 3)"));
}

TEST(ListCommandTest, CommandsOnAMissingStoreFailClearly) {
  ScratchDir dir;
  const std::string db = (dir / "absent.db").string();
  for (const std::string& command : {"list --db " + db, "delete --db " + db + " obj1",
                                     "backup --db " + db + " --to " + (dir / "b.db").string()}) {
    const testing::CommandResult result = RunOrbit(command);
    EXPECT_EQ(result.exit_code, 1) << command;
    EXPECT_EQ(result.err, "orbit: model store " + db + " does not exist\n") << command;
  }
  EXPECT_FALSE(std::filesystem::exists(db));
}

}  // namespace
}  // namespace orbit
