// kill -9 in the middle of writing: the store reopens intact, every object in it is whole, and
// every write that was acknowledged before the kill is there (docs/design.md#service-behaviour:
// "when the server says OK, the object survives a kill -9").
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "tests/support/child_process.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::Acknowledged;
using testing::Child;
using testing::RawDatabase;
using testing::ScratchDir;
using testing::SyntheticObject;

// The checks after a crash, on the file as the next process finds it: SQLite's own integrity
// check, no view without its object, every object with all `views_per_object`, and every
// acknowledged object present. Returns the names present.
std::set<std::string> ExpectIntactAfterCrash(const std::filesystem::path& file,
                                             std::int64_t views_per_object,
                                             const std::set<std::string>& acknowledged) {
  std::set<std::string> present;
  {
    RawDatabase raw(file);  // opening replays the committed part of the write-ahead log
    EXPECT_EQ(raw.Text("PRAGMA integrity_check"), "ok");
    EXPECT_EQ(raw.Int("SELECT count(*) FROM views WHERE object_id NOT IN (SELECT id FROM objects)"),
              0);
    EXPECT_THAT(
        raw.Column("SELECT DISTINCT (SELECT count(*) FROM views v WHERE v.object_id = o.id) "
                   "FROM objects o"),
        ::testing::Each(std::to_string(views_per_object)));
    for (const std::string& name : raw.Column("SELECT name FROM objects")) present.insert(name);
  }
  for (const std::string& name : acknowledged) {
    EXPECT_TRUE(present.count(name)) << name << " was acknowledged, then lost";
  }
  SqliteModelStore reopened(file);  // quick_check and schema check pass too
  EXPECT_EQ(reopened.LoadAll().size(), present.size());
  return present;
}

TEST(StoreCrashTest, KillingAnImportMidwayLeavesOnlyWholeObjectsAndItResumes) {
  ScratchDir dir;
  const std::string db = (dir / "models.db").string();
  const std::string coil = (orbit::testing::DataDir() / "coil-100").string();
  auto import = [&] {
    const std::string binary = orbit::testing::OrbitBinary();
    ::execl(binary.c_str(), binary.c_str(), "import", "--db", db.c_str(), "--layout", "coil100",
            "--data", coil.c_str(), "--objects", "1-12", "--threads", "1",
            static_cast<char*>(nullptr));
    return 127;
  };

  std::vector<std::string> lines;
  {
    Child child(import);
    while (Acknowledged(lines).size() < 3) {
      lines.push_back(child.ReadLine());
      ASSERT_FALSE(lines.back().empty()) << "import ended early";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(150));  // into the next object
    ASSERT_TRUE(child.Kill(lines)) << "import finished before the kill";
  }

  const std::set<std::string> acknowledged = Acknowledged(lines);
  const std::set<std::string> present = ExpectIntactAfterCrash(db, 72, acknowledged);
  EXPECT_LT(present.size(), 12u);

  // Run again, it carries on: the objects already there are skipped, the rest enrolled.
  const orbit::testing::CommandResult resumed =
      orbit::testing::RunCommand(orbit::testing::OrbitBinary() + " import --db " + db +
                                 " --layout coil100 --data " + coil + " --objects 1-12");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.out, ::testing::HasSubstr("skipped obj1 (already in the store as id 1)"));
  EXPECT_EQ(ExpectIntactAfterCrash(db, 72, {}).size(), 12u);
}

// Large transactions (1024 views with 16 KB thumbnails: 16 MB each) make the kill land inside a
// commit in progress rather than between two.
TEST(StoreCrashTest, KillingAWriterInsideALargeTransactionLosesOnlyTheUnacknowledgedObject) {
  ScratchDir dir;
  const std::filesystem::path db = dir / "models.db";
  { SqliteModelStore create(db, {.create_if_missing = true}); }
  auto write_forever = [&] {
    SqliteModelStore store(db);
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
  const std::set<std::string> present = ExpectIntactAfterCrash(db, 1024, acknowledged);
  // At most one object committed without its line printed yet.
  EXPECT_LE(present.size(), acknowledged.size() + 1);
}

}  // namespace
}  // namespace orbit
