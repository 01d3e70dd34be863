// orbit import (cli/import_command.cc) as an operator runs it, on real images: into a store
// file (COIL-100 and manifest layouts) and onto a real `orbit serve` process.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/connection.h"
#include "client/image_file.h"
#include "client/models_client.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/distractor_objects.h"
#include "storage/sqlite_model_store.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilDir;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::OrbitBinary;
using testing::OutputLines;
using testing::RunCommand;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::ServerProcess;
using testing::UnindentedLines;

// A store made with another variant (e.g. cedd-lire, the default before cedd-robust) keeps it:
// import adds to it in its variant, refuses to mix another in, and a server started on it
// without --variant serves it; a new store gets the product's variant.
TEST(ImportCommandTest, AnExistingStoreKeepsItsVariantAndANewOneGetsTheProducts) {
  ScratchDir dir;
  const std::string lire_db = (dir / "lire.db").string();
  const std::string coil = " --layout coil100 --data " + CoilDir();
  ASSERT_EQ(
      RunOrbit("import --db " + lire_db + coil + " --objects 1 --variant cedd-lire").exit_code, 0);
  ASSERT_EQ(RunOrbit("import --db " + lire_db + coil + " --objects 2").exit_code, 0);
  const auto mixed =
      RunOrbit("import --db " + lire_db + coil + " --objects 3 --variant cedd-robust");
  EXPECT_EQ(mixed.exit_code, 1);
  EXPECT_THAT(mixed.err, ::testing::HasSubstr("--variant cedd-robust is not the variant of the "
                                              "objects in " +
                                              lire_db + " (cedd-lire)"));
  EXPECT_THAT(OutputLines(RunOrbit("list --db " + lire_db).out),
              ::testing::ElementsAre(::testing::StartsWith("1 obj1 cedd-lire 72"),
                                     ::testing::StartsWith("2 obj2 cedd-lire 72")));
  {
    ServerProcess server({.database = dir / "lire.db"});
    const auto info = RunOrbit("info --json --server " + server.address());
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_EQ(nlohmann::json::parse(info.out)["variant"], "cedd-lire");
  }
  const std::string new_db = (dir / "new.db").string();
  ASSERT_EQ(RunOrbit("import --db " + new_db + coil + " --objects 4").exit_code, 0);
  EXPECT_THAT(RunOrbit("list --db " + new_db).out,
              ::testing::StartsWith("1 obj4 cedd-soft-hsv-hog 72"));
}

TEST(ImportCommandTest, ImportStoresLireDescriptorsAndTypicalDistances) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  ASSERT_EQ(RunOrbit("import --db " + db + " --layout coil100 --data " + CoilDir() +
                     " --objects 7 --variant cedd-lire")
                .exit_code,
            0);

  SqliteModelStore store(db);
  const std::vector<ObjectModel> models = store.LoadAll();
  ASSERT_EQ(models.size(), 1u);
  ASSERT_EQ(models[0].views.size(), 72u);
  // Every view's descriptor is LIRE's own for that image (the reference file), at its azimuth.
  std::map<std::string, DescriptorValues> reference;
  for (const auto& ref :
       testing::ReadReferenceVectors(testing::DataDir() / "coil-100-lire-cedd.txt")) {
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

TEST(ImportCommandTest, ImportFromAManifestWithElevationsAndVariant) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  std::ofstream(dir / "set.csv") << "object,path,azimuth,elevation\n"
                                 << "mug," << CoilDir() << "/obj5__0.png,0,\n"
                                 << "cup," << CoilDir() << "/obj6__0.png,-30,12.5\n"
                                 << "mug," << CoilDir() << "/obj5__90.png,90,\n";

  const testing::CommandResult imported =
      RunOrbit("import --db " + db + " --layout manifest --manifest " + (dir / "set.csv").string() +
               " --variant cedd-full");

  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  // Each object with what its enrollment got: mug's views at 0 and 90 leave two gaps, cup's one
  // view the whole circle; cup is compared with mug, enrolled before it.
  const std::vector<std::string> lines = OutputLines(imported.out);
  ASSERT_EQ(lines.size(), 5u) << imported.out;
  EXPECT_EQ(lines[0], "enrolled mug (id 1, 2 views)");
  EXPECT_EQ(lines[1], "  coverage: 2 gaps wider than 30 degrees: 0-90 (90), 90-0 (270)");
  EXPECT_EQ(lines[2], "enrolled cup (id 2, 1 views)");
  EXPECT_EQ(lines[3], "  coverage: 1 gap wider than 30 degrees: 330-330 (360)");
  EXPECT_THAT(lines[4], ::testing::StartsWith("  confusable: mug (similarity 0."));
  SqliteModelStore store(db);
  const StoredObject cup = *store.Get(2);
  EXPECT_EQ(cup.summary.variant, DescriptorVariant::kCeddFull);
  EXPECT_EQ(cup.views[0].azimuth, 330.0);
  EXPECT_EQ(cup.views[0].elevation, 12.5);
  EXPECT_EQ(store.Get(1)->views[1].elevation, std::nullopt);
}

TEST(ImportCommandTest, ImportRefusesABadObjectNameBeforeWritingAnything) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  std::ofstream(dir / "set.csv") << "path,object,azimuth\n"
                                 << CoilDir() << "/obj5__0.png,mug,0\n"
                                 << CoilDir() << "/obj6__0.png,red/cup,0\n";

  const testing::CommandResult imported =
      RunOrbit("import --db " + db + " --layout manifest --manifest " + (dir / "set.csv").string());

  EXPECT_EQ(imported.exit_code, 1);
  EXPECT_THAT(imported.err, HasSubstr("object name \"red/cup\" has a character not allowed"));
  EXPECT_FALSE(std::filesystem::exists(db));
}

// With --boxes (a dataset's boxes.csv), each image's object region is described: its box grown
// by --box-margin and clipped to the image, the pixels `orbit enroll --box` and
// `orbit eval --boxes` describe. A box outside its image is refused, naming the file and line,
// before anything is written.
TEST(ImportCommandTest, ImportWithBoxesDescribesEachImagesObjectRegion) {
  ScratchDir dir;
  const std::string eth = (testing::DataDir() / "eth-80-dev").string();
  const std::string apple = eth + "/images/apple1-090-000.jpg";  // 256x256, box 32,32,192,191
  const std::string car = eth + "/images/car1-090-000.jpg";      // 256x256, box 29,93,198,70
  const std::string manifest =
      dir.Write("set.csv", "path,object,azimuth\n" + apple + ",apple,0\n" + car + ",car,0\n")
          .string();
  const std::string import = "import --layout manifest --manifest " + manifest;
  const std::string db = (dir / "models.db").string();
  const std::string tight_db = (dir / "tight.db").string();
  const auto grown = RunOrbit(import + " --db " + db + " --boxes " + eth + "/boxes.csv");
  ASSERT_EQ(grown.exit_code, 0) << grown.err;
  const auto tight =
      RunOrbit(import + " --db " + tight_db + " --boxes " + eth + "/boxes.csv --box-margin 0");
  ASSERT_EQ(tight.exit_code, 0) << tight.err;

  // By hand: a tenth of the box a side, round(19.2) = 19 and round(19.1) = 19 for the apple,
  // round(19.8) = 20 and 7 for the car; no margin, the box itself.
  const auto expect_region = [](const std::string& db, const std::string& object,
                                const std::string& image, const cv::Rect& region) {
    SqliteModelStore store(db);
    const std::optional<StoredObject> stored = store.Get(store.Find(object)->id);
    ASSERT_EQ(stored->views.size(), 1u);
    const ViewDescription expected = DescribeView(ReadImageFile(image)(region), Product().variant);
    EXPECT_EQ(stored->views[0].descriptor, expected.descriptor) << db << " " << object;
    EXPECT_EQ(stored->views[0].typical_distance, expected.typical_distance) << db << " " << object;
  };
  expect_region(db, "apple", apple, cv::Rect(13, 13, 230, 229));
  expect_region(db, "car", car, cv::Rect(9, 86, 238, 84));
  expect_region(tight_db, "apple", apple, cv::Rect(32, 32, 192, 191));
  expect_region(tight_db, "car", car, cv::Rect(29, 93, 198, 70));

  // The same boxes as columns of the manifest: the same regions, with the default margin or
  // --box-margin's.
  const std::string boxed_manifest =
      dir.Write("boxed.csv", "path,object,azimuth,x,y,w,h\n" + apple + ",apple,0,32,32,192,191\n" +
                                 car + ",car,0,29,93,198,70\n")
          .string();
  const std::string columns_db = (dir / "columns.db").string();
  const std::string columns_tight_db = (dir / "columns-tight.db").string();
  const std::string import_boxed = "import --layout manifest --manifest " + boxed_manifest;
  ASSERT_EQ(RunOrbit(import_boxed + " --db " + columns_db).exit_code, 0);
  ASSERT_EQ(RunOrbit(import_boxed + " --db " + columns_tight_db + " --box-margin 0").exit_code, 0);
  expect_region(columns_db, "apple", apple, cv::Rect(13, 13, 230, 229));
  expect_region(columns_db, "car", car, cv::Rect(9, 86, 238, 84));
  expect_region(columns_tight_db, "car", car, cv::Rect(29, 93, 198, 70));
  // Boxes in the manifest and in a boxes file: which one is meant is not guessed.
  const auto both = RunOrbit(import_boxed + " --db " + (dir / "both.db").string() + " --boxes " +
                             eth + "/boxes.csv");
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_THAT(both.err, HasSubstr(boxed_manifest + ":2): give boxes in the manifest or in a "
                                                   "boxes file, not both"));

  // The car's box runs off the bottom: refused before the apple is enrolled.
  const std::string bad_db = (dir / "bad.db").string();
  const std::string boxes = dir.Write("boxes.csv", "path,x,y,w,h\n" + apple + ",32,32,192,191\n" +
                                                       car + ",29,93,198,170\n")
                                .string();
  const auto refused = RunOrbit(import + " --db " + bad_db + " --boxes " + boxes);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr(boxes + ":3: y+h must be at most the image's height 256"));
  EXPECT_EQ(refused.out, "");
  EXPECT_FALSE(std::filesystem::exists(bad_db));
}

// Every line of `orbit list` without its last column (updated_at).
std::vector<std::string> WithoutTimestamps(const std::string& listing) {
  std::vector<std::string> lines = OutputLines(listing);
  for (std::string& line : lines) line = line.substr(0, line.rfind(' '));
  return lines;
}

TEST(ImportCommandTest, ImportListAndDeleteWorkOnAServerAsOnAFile) {
  ServerProcess server;
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  const std::string coil = " --layout coil100 --data " + (testing::DataDir() / "coil-100").string();
  const auto imported = RunCommand(orbit + "import" + at + coil + " --objects 1-2");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_EQ(UnindentedLines(imported.out),
            (std::vector<std::string>{"enrolled obj1 (id 1, 72 views)",
                                      "enrolled obj2 (id 2, 72 views)"}));
  EXPECT_NE(imported.err.find("2 objects enrolled, 0 already present, on " + server.address()),
            std::string::npos)
      << imported.err;
  const auto resumed = RunCommand(orbit + "import" + at + coil + " --objects 1-3");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(UnindentedLines(resumed.out),
            (std::vector<std::string>{"skipped obj1 (already on the server as id 1)",
                                      "skipped obj2 (already on the server as id 2)",
                                      "enrolled obj3 (id 3, 72 views)"}));

  // The same import into a file stores the very same views (same descriptors, same seeded
  // typical distances), and both list alike.
  const testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  const std::string db = (dir / "models.db").string();
  ASSERT_EQ(RunCommand(orbit + "import --db " + db + coil + " --objects 1-3").exit_code, 0);
  {
    SqliteModelStore store(db);
    const std::optional<StoredObject> local = store.Get(2);
    ASSERT_TRUE(local.has_value());
    const Connection connection(testing::At(server.address()));
    const v1::GetObjectResponse remote = ModelsClient(connection).GetObject(ObjectById(2), true);
    ASSERT_EQ(remote.views_size(), static_cast<int>(local->views.size()));
    for (int f = 0; f < remote.views_size(); ++f) {
      const ModelView& view = local->views[f];
      const std::string cedd(view.descriptor.begin(), view.descriptor.begin() + kCeddSize);
      EXPECT_EQ(remote.views(f).cedd(), cedd);
      EXPECT_EQ(remote.views(f).azimuth_deg(), view.azimuth);
      EXPECT_DOUBLE_EQ(remote.views(f).typical_distance(), view.typical_distance);
    }
  }
  const auto listed_remote = RunCommand(orbit + "list" + at);
  const auto listed_local = RunCommand(orbit + "list --db " + db);
  ASSERT_EQ(listed_remote.exit_code, 0) << listed_remote.err;
  EXPECT_EQ(WithoutTimestamps(listed_remote.out), WithoutTimestamps(listed_local.out));
  EXPECT_EQ(WithoutTimestamps(listed_remote.out)[2], "3 obj3 cedd-soft-hsv-hog 72");
  const auto json = RunCommand(orbit + "list --json" + at);
  ASSERT_EQ(OutputLines(json.out).size(), 3u);
  EXPECT_EQ(nlohmann::json::parse(OutputLines(json.out)[0])["name"], "obj1");

  const auto deleted = RunCommand(orbit + "delete" + at + " obj2");
  ASSERT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_EQ(deleted.out, "deleted obj2 (id 2, 72 views)\n");
  const auto missing = RunCommand(orbit + "delete" + at + " obj2");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("no object named \"obj2\" on " + server.address()), std::string::npos)
      << missing.err;
  EXPECT_EQ(OutputLines(RunCommand(orbit + "list" + at).out).size(), 2u);

  // One of --db and --server, and the server's variant.
  const auto neither = RunCommand(orbit + "list");
  EXPECT_EQ(neither.exit_code, 1);
  EXPECT_NE(neither.err.find("give --db FILE (a local model store) or --server HOST:PORT"),
            std::string::npos)
      << neither.err;
  EXPECT_NE(RunCommand(orbit + "list --db " + db + at).exit_code, 0);
  const auto variant =
      RunCommand(orbit + "import" + at + coil + " --objects 4 --variant cedd-full");
  EXPECT_EQ(variant.exit_code, 1);
  EXPECT_NE(variant.err.find("--variant cedd-full is not the server's (cedd-soft-hsv-hog)"),
            std::string::npos)
      << variant.err;
}

// Generated objects import as a dataset's do: one line per durable object, a second run
// carries on where the first stopped, and the views are those `orbit eval --distractors` adds
// (DistractorObjects of the import's seed). Without a selection, or beyond the generator's
// range, nothing is written.
TEST(ImportCommandTest, DistractorsImportGeneratedObjectsAndResume) {
  const ScratchDir scratch;
  const std::string db = (scratch.path() / "catalogue.db").string();
  const std::string import = "import --db " + db + " --layout distractors --threads 2";
  const auto first = RunOrbit(import + " --objects 1-2");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(UnindentedLines(first.out),
            (std::vector<std::string>{"enrolled distractor1 (id 1, 72 views)",
                                      "enrolled distractor2 (id 2, 72 views)"}));
  const auto resumed = RunOrbit(import + " --objects 2-3");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(UnindentedLines(resumed.out),
            (std::vector<std::string>{"skipped distractor2 (already in the store as id 2)",
                                      "enrolled distractor3 (id 3, 72 views)"}));
  {
    SqliteModelStore store(db);
    const std::optional<StoredObject> third = store.Get(3);
    ASSERT_TRUE(third.has_value());
    const std::vector<ModelView> generated =
        DistractorObjects(kDefaultViewNoiseSeed, 1).Views(3, Product().variant, 1);
    ASSERT_EQ(third->views.size(), generated.size());
    for (std::size_t f = 0; f < generated.size(); ++f) {
      EXPECT_EQ(third->views[f].descriptor, generated[f].descriptor) << "view " << f;
      EXPECT_EQ(third->views[f].azimuth, generated[f].azimuth);
      EXPECT_DOUBLE_EQ(third->views[f].typical_distance, generated[f].typical_distance);
    }
  }
  const std::string none = (scratch.path() / "none.db").string();
  const auto unselected = RunOrbit("import --db " + none + " --layout distractors");
  EXPECT_EQ(unselected.exit_code, 1);
  EXPECT_THAT(unselected.err, HasSubstr("--layout distractors needs --objects, e.g. 1-10000"));
  const auto beyond =
      RunOrbit("import --db " + none + " --layout distractors --objects 99999-100001");
  EXPECT_EQ(beyond.exit_code, 1);
  EXPECT_THAT(beyond.err, HasSubstr("distractor numbers are 1..100000, got 100001"));
  EXPECT_FALSE(std::filesystem::exists(none));
}

}  // namespace
}  // namespace orbit
