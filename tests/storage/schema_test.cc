// The store creates and migrates its own schema (storage/schema.h): from an empty file, from a
// hand-made version-1 database as the first release wrote it, each migration all or nothing; and
// it refuses, changing nothing, files it must not touch.
#include "storage/schema.h"

#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::RawDatabase;
using testing::ScratchDir;
using testing::SyntheticObject;
using testing::SyntheticView;

// The version-1 schema exactly as version 1 of the program created it (frozen here on purpose:
// the migration must work on the files that release wrote, whatever schema.cc says today).
constexpr const char* kVersion1Schema = R"sql(
  CREATE TABLE schema_version (version INTEGER PRIMARY KEY, applied_at TEXT NOT NULL) STRICT;
  CREATE TABLE objects (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    name TEXT NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
    variant TEXT NOT NULL CHECK (variant IN ('cedd-lire', 'cedd-full')),
    created_at TEXT NOT NULL,
    updated_at TEXT NOT NULL
  ) STRICT;
  CREATE TABLE views (
    id INTEGER PRIMARY KEY,
    object_id INTEGER NOT NULL REFERENCES objects (id) ON DELETE CASCADE,
    azimuth REAL NOT NULL CHECK (azimuth >= 0 AND azimuth < 360),
    elevation REAL CHECK (elevation BETWEEN -90 AND 90),
    descriptor BLOB NOT NULL CHECK (length(descriptor) = 144),
    typical_distance REAL NOT NULL CHECK (typical_distance BETWEEN 0 AND 1)
  ) STRICT;
  CREATE INDEX views_by_object ON views (object_id, azimuth);
  INSERT INTO schema_version VALUES (1, '2024-01-01T00:00:00.000Z');
)sql";

// A CEDD variant's blob: its 144 values.
std::string HexBlob(const DescriptorValues& values) {
  std::ostringstream hex;
  hex << "X'";
  for (std::uint8_t v : DescriptorBytes(values, DescriptorVariant::kCeddFull)) {
    hex << '0' << static_cast<int>(v);  // values are 0..7
  }
  hex << "'";
  return hex.str();
}

// A version-1 store holding object 7 "mug" (cedd-full) with two views.
void WriteVersion1Store(const std::filesystem::path& file) {
  RawDatabase raw(file);
  raw.Execute(kVersion1Schema);
  raw.Execute(
      "INSERT INTO objects VALUES (7, 'mug', 'cedd-full', '2024-01-02T03:04:05.006Z', "
      "'2024-01-02T03:04:05.006Z');"
      "INSERT INTO views VALUES (1, 7, 90, NULL, " +
      HexBlob(SyntheticView(1, 0).descriptor) +
      ", 0.125);"
      "INSERT INTO views VALUES (2, 7, 45, 10.5, " +
      HexBlob(SyntheticView(2, 0).descriptor) + ", 0.25);");
}

std::string ReadBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The StoreError `open` throws; fails the test when there is none.
template <typename Open>
StoreError ErrorOnOpen(Open open) {
  try {
    open();
  } catch (const StoreError& e) {
    return e;
  }
  ADD_FAILURE() << "opened";
  return StoreError(StoreError::Code::kInternal, "");
}

TEST(SchemaMigrationTest, AnEmptyFileBecomesACurrentStore) {
  ScratchDir dir;
  std::ofstream(dir / "empty.db").close();  // zero bytes: what `touch` makes
  {
    SqliteModelStore store(dir / "empty.db");
    EXPECT_EQ(store.Enroll(SyntheticObject("mug", 2)), 1);
  }
  RawDatabase raw(dir / "empty.db");
  EXPECT_THAT(raw.Column("SELECT version FROM schema_version ORDER BY version"),
              ElementsAre("1", "2", "3", "4", "5", "6"));
  EXPECT_THAT(raw.Column("SELECT name FROM pragma_table_info('objects')"),
              ElementsAre("id", "name", "variant", "created_at", "updated_at", "metadata"));
  EXPECT_THAT(raw.Column("SELECT name FROM pragma_table_info('views')"),
              ElementsAre("id", "object_id", "azimuth", "elevation", "descriptor",
                          "typical_distance", "thumbnail"));
  EXPECT_EQ(raw.Text("PRAGMA journal_mode"), "wal");  // persistent in the file
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views"), 2);
}

TEST(SchemaMigrationTest, AVersion1StoreIsMigratedWithItsDataIntact) {
  ScratchDir dir;
  WriteVersion1Store(dir / "v1.db");

  SqliteModelStore store(dir / "v1.db");

  const std::optional<StoredObject> mug = store.Get(7);
  ASSERT_TRUE(mug.has_value());
  EXPECT_EQ(mug->summary.name, "mug");
  EXPECT_EQ(mug->summary.variant, DescriptorVariant::kCeddFull);
  EXPECT_EQ(mug->summary.created_at, "2024-01-02T03:04:05.006Z");
  EXPECT_EQ(mug->summary.metadata, "{}");
  ASSERT_EQ(mug->views.size(), 2u);
  EXPECT_EQ(mug->views[0].azimuth, 45.0);
  EXPECT_EQ(mug->views[0].elevation, 10.5);
  EXPECT_EQ(mug->views[0].typical_distance, 0.25);
  EXPECT_EQ(mug->views[0].descriptor, SyntheticView(2, 0).descriptor);
  EXPECT_EQ(mug->views[1].descriptor, SyntheticView(1, 0).descriptor);
  EXPECT_THAT(mug->thumbnails, ElementsAre("", ""));
  // The new columns work, and ids carry on after the old ones.
  Enrollment cup = SyntheticObject("cup", 1);
  cup.metadata = R"({"owner": "lab"})";
  cup.thumbnails = {"png"};
  EXPECT_EQ(store.Enroll(cup), 8);
  EXPECT_EQ(store.Get(8)->thumbnails[0], "png");
  RawDatabase raw(dir / "v1.db");
  EXPECT_THAT(raw.Column("SELECT version FROM schema_version ORDER BY version"),
              ElementsAre("1", "2", "3", "4", "5", "6"));
  EXPECT_EQ(raw.Text("SELECT applied_at FROM schema_version WHERE version = 1"),
            "2024-01-01T00:00:00.000Z");
}

// Migration 3 rebuilds the objects table: the views must survive it (no cascade), the ids of
// deleted objects must stay unused, and the rebuilt table must keep its rules and accept the
// new variant.
TEST(SchemaMigrationTest, RebuildingTheObjectsTableKeepsViewsIdsAndCascades) {
  ScratchDir dir;
  WriteVersion1Store(dir / "v1.db");
  {
    RawDatabase raw(dir / "v1.db");  // object 9 came and went: its id must never come back
    raw.Execute(
        "INSERT INTO objects VALUES (9, 'gone', 'cedd-lire', '2024-01-03T00:00:00.000Z', "
        "'2024-01-03T00:00:00.000Z'); DELETE FROM objects WHERE id = 9;");
  }

  SqliteModelStore store(dir / "v1.db");

  EXPECT_EQ(store.Get(7)->views.size(), 2u);
  Enrollment robust = SyntheticObject("robust-cup", 3);
  robust.variant = DescriptorVariant::kCeddRobust;
  EXPECT_EQ(store.Enroll(robust), 10);
  EXPECT_EQ(store.Get(10)->summary.variant, DescriptorVariant::kCeddRobust);
  Enrollment layout = SyntheticObject("layout-cup", 1);  // migration 5's variant
  layout.variant = DescriptorVariant::kCeddHsvLayout;
  EXPECT_EQ(store.Enroll(layout), 11);
  EXPECT_EQ(store.Get(11)->summary.variant, DescriptorVariant::kCeddHsvLayout);
  RawDatabase raw(dir / "v1.db");
  EXPECT_EQ(raw.Int("SELECT count(*) FROM pragma_foreign_key_check"), 0);
  EXPECT_THAT(raw.Column("SELECT name FROM sqlite_schema WHERE type = 'table' AND name LIKE "
                         "'objects%'"),
              ElementsAre("objects"));
  store.Delete(7);  // ON DELETE CASCADE still holds on the rebuilt table
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views WHERE object_id = 7"), 0);
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views WHERE object_id = 10"), 3);
  EXPECT_THROW(raw.Execute("INSERT INTO objects (name, variant, created_at, updated_at) VALUES "
                           "('x', 'sift', 'a', 'b')"),
               std::exception);
}

TEST(SchemaMigrationTest, AFailedMigrationLeavesThePreviousVersionWhole) {
  ScratchDir dir;
  WriteVersion1Store(dir / "v1.db");
  {
    // Someone added a column by hand that migration 2 also adds, after the one it adds first.
    RawDatabase raw(dir / "v1.db");
    raw.Execute("ALTER TABLE views ADD COLUMN thumbnail TEXT");
  }

  const StoreError error = ErrorOnOpen([&] { SqliteModelStore store(dir / "v1.db"); });

  EXPECT_THAT(error.what(), HasSubstr("duplicate column name: thumbnail"));
  RawDatabase raw(dir / "v1.db");
  EXPECT_EQ(raw.Int("SELECT max(version) FROM schema_version"), 1);
  // Migration 2's first step (objects.metadata) was rolled back with the rest.
  EXPECT_EQ(raw.Int("SELECT count(*) FROM pragma_table_info('objects') WHERE name = 'metadata'"),
            0);
  EXPECT_EQ(raw.Int("SELECT count(*) FROM views"), 2);
}

TEST(SchemaMigrationTest, ANewerStoreIsRefusedUntouched) {
  ScratchDir dir;
  WriteVersion1Store(dir / "future.db");
  {
    RawDatabase raw(dir / "future.db");
    raw.Execute("INSERT INTO schema_version VALUES (" + std::to_string(kSchemaVersion + 1) +
                ", '2031-01-01T00:00:00.000Z')");
  }

  const StoreError error = ErrorOnOpen([&] { SqliteModelStore store(dir / "future.db"); });

  EXPECT_EQ(error.code(), StoreError::Code::kIncompatible);
  EXPECT_EQ(std::string(error.what()),
            "cannot open model store " + (dir / "future.db").string() + ": " +
                (dir / "future.db").string() + " has schema version " +
                std::to_string(kSchemaVersion + 1) + ", newer than the versions 1.." +
                std::to_string(kSchemaVersion) + " this program knows: use a newer orbit");
  RawDatabase raw(dir / "future.db");
  EXPECT_EQ(raw.Int("SELECT count(*) FROM pragma_table_info('objects') WHERE name = 'metadata'"),
            0);
}

TEST(SchemaMigrationTest, ADatabaseOfSomethingElseIsRefusedUntouched) {
  ScratchDir dir;
  {
    RawDatabase raw(dir / "shop.db");
    raw.Execute("CREATE TABLE customers (id INTEGER PRIMARY KEY, name TEXT)");
  }

  const StoreError error = ErrorOnOpen([&] { SqliteModelStore store(dir / "shop.db"); });

  EXPECT_EQ(error.code(), StoreError::Code::kIncompatible);
  EXPECT_THAT(error.what(),
              HasSubstr("is not an Orbit model store: it holds tables but no schema_version"));
  RawDatabase raw(dir / "shop.db");
  EXPECT_THAT(raw.Column("SELECT name FROM sqlite_schema"), ElementsAre("customers"));
}

TEST(SchemaMigrationTest, AFileThatIsNotADatabaseIsRefusedUntouched) {
  ScratchDir dir;
  const std::string text = "path,object,azimuth\nimg.png,mug,0\n" + std::string(200, '#');
  std::ofstream(dir / "models.csv") << text;

  const StoreError error = ErrorOnOpen([&] { SqliteModelStore store(dir / "models.csv"); });

  EXPECT_EQ(error.code(), StoreError::Code::kCorrupt);
  EXPECT_THAT(error.what(), HasSubstr("models.csv"));
  EXPECT_THAT(error.what(), HasSubstr("file is not a database"));
  EXPECT_EQ(ReadBytes(dir / "models.csv"), text);
}

TEST(SchemaMigrationTest, ADamagedStoreFailsTheCheckOnOpen) {
  ScratchDir dir;
  {
    SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
    for (int i = 0; i < 20; ++i) store.Enroll(SyntheticObject("obj" + std::to_string(i), 72, i));
  }
  RawDatabase raw(dir / "models.db");
  const std::int64_t page_size = raw.Int("PRAGMA page_size");
  const std::int64_t pages = raw.Int("PRAGMA page_count");
  ASSERT_GT(pages, 20);
  {
    // Overwrite a page in the middle of the file, as a failing disk might.
    std::fstream file(dir / "models.db", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(page_size * (pages / 2));
    const std::string garbage(static_cast<std::size_t>(page_size), '\x5a');
    file.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }

  const StoreError error = ErrorOnOpen([&] { SqliteModelStore store(dir / "models.db"); });

  EXPECT_EQ(error.code(), StoreError::Code::kCorrupt);
  EXPECT_THAT(error.what(), HasSubstr("PRAGMA quick_check failed"));
}

}  // namespace
}  // namespace orbit
