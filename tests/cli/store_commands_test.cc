// The offline store commands as an operator runs them: orbit import (COIL-100 and manifest),
// list, delete and backup, on real images and real store files.
#include <fstream>
#include <map>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/image_file.h"
#include "core/view_description.h"
#include "storage/sqlite_model_store.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using testing::ScratchDir;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

testing::CommandResult Orbit(const std::string& arguments) {
  return testing::RunCommand(testing::OrbitBinary() + " " + arguments);
}

std::string Coil() { return (testing::DataDir() / "coil-100").string(); }

TEST(StoreCommandsTest, ImportListDeleteAndBackupCoil100) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();

  const testing::CommandResult imported =
      Orbit("import --db " + db + " --layout coil100 --data " + Coil() + " --objects 1-3");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_THAT(Lines(imported.out),
              ElementsAre("enrolled obj1 (id 1, 72 views)", "enrolled obj2 (id 2, 72 views)",
                          "enrolled obj3 (id 3, 72 views)"));
  EXPECT_THAT(imported.err, HasSubstr("3 objects enrolled, 0 already present"));

  const testing::CommandResult listed = Orbit("list --db " + db);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_THAT(Lines(listed.out),
              ElementsAre(MatchesRegex("1 obj1 cedd-lire 72 [-0-9T:.]+Z"),
                          MatchesRegex("2 obj2 cedd-lire 72 [-0-9T:.]+Z"),
                          MatchesRegex("3 obj3 cedd-lire 72 [-0-9T:.]+Z")));

  const testing::CommandResult json = Orbit("list --db " + db + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const std::vector<std::string> json_lines = Lines(json.out);
  ASSERT_EQ(json_lines.size(), 3u);
  const nlohmann::json second = nlohmann::json::parse(json_lines[1]);
  EXPECT_EQ(second["id"], 2);
  EXPECT_EQ(second["name"], "obj2");
  EXPECT_EQ(second["variant"], "cedd-lire");
  EXPECT_EQ(second["views"], 72);
  EXPECT_EQ(second["metadata"], nlohmann::json::object());

  const testing::CommandResult deleted = Orbit("delete --db " + db + " obj2");
  EXPECT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_EQ(deleted.out, "deleted obj2 (id 2, 72 views)\n");
  const testing::CommandResult again = Orbit("delete --db " + db + " obj2");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_EQ(again.err, "orbit delete: no object named \"obj2\" in " + db + "\n");

  const std::string backup = (dir / "backup.db").string();
  const testing::CommandResult backed_up = Orbit("backup --db " + db + " --to " + backup);
  EXPECT_EQ(backed_up.exit_code, 0) << backed_up.err;
  EXPECT_THAT(backed_up.out, HasSubstr("backed up " + db + " to " + backup));
  const testing::CommandResult from_backup = Orbit("list --db " + backup);
  EXPECT_EQ(from_backup.out, Orbit("list --db " + db).out);
  EXPECT_EQ(Lines(from_backup.out).size(), 2u);

  // Importing again enrolls only what is missing.
  const testing::CommandResult resumed =
      Orbit("import --db " + db + " --layout coil100 --data " + Coil() + " --objects 1-3");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(Lines(resumed.out),
              ElementsAre("skipped obj1 (already in the store as id 1)",
                          "enrolled obj2 (id 4, 72 views)",
                          "skipped obj3 (already in the store as id 3)"));
}

TEST(StoreCommandsTest, ImportStoresLireDescriptorsAndTypicalDistances) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  ASSERT_EQ(Orbit("import --db " + db + " --layout coil100 --data " + Coil() + " --objects 7")
                .exit_code,
            0);

  SqliteModelStore store(db);
  const std::vector<ObjectModel> models = store.LoadAll();
  ASSERT_EQ(models.size(), 1u);
  ASSERT_EQ(models[0].views.size(), 72u);
  // Every view's descriptor is LIRE's own for that image (the reference file), at its azimuth.
  std::map<std::string, DescriptorValues> reference;
  for (const auto& ref : testing::ReadReferenceVectors(testing::DataDir() / "coil-100-lire-cedd.txt")) {
    reference[ref.path] = ref.values;
  }
  for (const ModelView& view : models[0].views) {
    const std::string path = "coil-100/obj7__" + std::to_string(int(view.azimuth)) + ".png";
    EXPECT_EQ(view.descriptor, reference.at(path)) << path;
  }
  EXPECT_EQ(models[0].views[2].azimuth, 10.0);
  // Ttyp of the view at 10 degrees is DescribeView's with the default base seed: what the
  // client library and a server store for the same image.
  const cv::Mat image = ReadImageFile((testing::DataDir() / "coil-100/obj7__10.png").string());
  EXPECT_EQ(models[0].views[2].typical_distance,
            DescribeView(image, DescriptorVariant::kCeddLire).typical_distance);
  EXPECT_GT(models[0].views[2].typical_distance, 0.0);
}

TEST(StoreCommandsTest, ImportFromAManifestWithElevationsAndVariant) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  std::ofstream(dir / "set.csv") << "object,path,azimuth,elevation\n"
                                 << "mug," << Coil() << "/obj5__0.png,0,\n"
                                 << "cup," << Coil() << "/obj6__0.png,-30,12.5\n"
                                 << "mug," << Coil() << "/obj5__90.png,90,\n";

  const testing::CommandResult imported =
      Orbit("import --db " + db + " --layout manifest --manifest " + (dir / "set.csv").string() +
            " --variant cedd-full");

  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_THAT(Lines(imported.out),
              ElementsAre("enrolled mug (id 1, 2 views)", "enrolled cup (id 2, 1 views)"));
  SqliteModelStore store(db);
  const StoredObject cup = *store.Get(2);
  EXPECT_EQ(cup.summary.variant, DescriptorVariant::kCeddFull);
  EXPECT_EQ(cup.views[0].azimuth, 330.0);
  EXPECT_EQ(cup.views[0].elevation, 12.5);
  EXPECT_EQ(store.Get(1)->views[1].elevation, std::nullopt);
}

TEST(StoreCommandsTest, ImportRefusesABadObjectNameBeforeWritingAnything) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  std::ofstream(dir / "set.csv") << "path,object,azimuth\n"
                                 << Coil() << "/obj5__0.png,mug,0\n"
                                 << Coil() << "/obj6__0.png,red/cup,0\n";

  const testing::CommandResult imported = Orbit(
      "import --db " + db + " --layout manifest --manifest " + (dir / "set.csv").string());

  EXPECT_EQ(imported.exit_code, 1);
  EXPECT_THAT(imported.err, HasSubstr("object name \"red/cup\" has a character not allowed"));
  EXPECT_FALSE(std::filesystem::exists(db));
}

TEST(StoreCommandsTest, CommandsOnAMissingStoreFailClearly) {
  ScratchDir dir;
  const std::string db = (dir / "absent.db").string();
  for (const std::string& command : {"list --db " + db, "delete --db " + db + " obj1",
                                     "backup --db " + db + " --to " + (dir / "b.db").string()}) {
    const testing::CommandResult result = Orbit(command);
    EXPECT_EQ(result.exit_code, 1) << command;
    EXPECT_EQ(result.err, "orbit: model store " + db + " does not exist\n") << command;
  }
  EXPECT_FALSE(std::filesystem::exists(db));
}

}  // namespace
}  // namespace orbit
