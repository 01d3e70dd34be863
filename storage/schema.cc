#include "storage/schema.h"

#include <iterator>
#include <string>

#include "storage/sqlite_transaction.h"
#include "storage/store_error.h"

namespace orbit {
namespace {

// migrations[v - 1] takes the schema from version v - 1 to v. Never edit a shipped migration:
// databases in the field were built by it; add a new one instead.
constexpr const char* kMigrations[] = {
    // 1: the recognition data. AUTOINCREMENT so that an id is never reused after a delete (a
    // client holding an old id must get NOT_FOUND, not another object). STRICT tables refuse
    // values of the wrong type; the CHECKs are the last line behind storage/model_validation.h.
    R"sql(
      CREATE TABLE schema_version (
        version INTEGER PRIMARY KEY,
        applied_at TEXT NOT NULL
      ) STRICT;
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
    )sql",
    // 2: the extras a user sees but the engines do not need.
    R"sql(
      ALTER TABLE objects ADD COLUMN metadata TEXT NOT NULL DEFAULT '{}'
        CHECK (json_valid(metadata) AND json_type(metadata) = 'object');
      ALTER TABLE views ADD COLUMN thumbnail BLOB CHECK (length(thumbnail) <= 65536);
    )sql",
    // 3: the cedd-robust variant. SQLite cannot widen a CHECK in place, so objects is rebuilt
    // (SQLite's documented table rebuild; MigrateSchema runs it with foreign keys off, so
    // dropping the old table deletes no views). The AUTOINCREMENT high-water mark is carried
    // over, so the ids of deleted objects are still never reused.
    R"sql(
      CREATE TABLE objects_v3 (
        id INTEGER PRIMARY KEY AUTOINCREMENT,
        name TEXT NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
        variant TEXT NOT NULL CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust')),
        created_at TEXT NOT NULL,
        updated_at TEXT NOT NULL,
        metadata TEXT NOT NULL DEFAULT '{}'
          CHECK (json_valid(metadata) AND json_type(metadata) = 'object')
      ) STRICT;
      INSERT INTO objects_v3 (id, name, variant, created_at, updated_at, metadata)
        SELECT id, name, variant, created_at, updated_at, metadata FROM objects;
      DELETE FROM sqlite_sequence WHERE name = 'objects_v3';
      INSERT INTO sqlite_sequence (name, seq)
        SELECT 'objects_v3', seq FROM sqlite_sequence WHERE name = 'objects';
      DROP TABLE objects;
      ALTER TABLE objects_v3 RENAME TO objects;
    )sql",
    // 4: the cedd-hsv-hog variant, whose descriptors are 480 bytes. Both tables are rebuilt as
    // in 3 (views keeps its ids; its index is rebuilt with it).
    R"sql(
      CREATE TABLE objects_v4 (
        id INTEGER PRIMARY KEY AUTOINCREMENT,
        name TEXT NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
        variant TEXT NOT NULL
          CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust', 'cedd-hsv-hog')),
        created_at TEXT NOT NULL,
        updated_at TEXT NOT NULL,
        metadata TEXT NOT NULL DEFAULT '{}'
          CHECK (json_valid(metadata) AND json_type(metadata) = 'object')
      ) STRICT;
      INSERT INTO objects_v4 (id, name, variant, created_at, updated_at, metadata)
        SELECT id, name, variant, created_at, updated_at, metadata FROM objects;
      DELETE FROM sqlite_sequence WHERE name = 'objects_v4';
      INSERT INTO sqlite_sequence (name, seq)
        SELECT 'objects_v4', seq FROM sqlite_sequence WHERE name = 'objects';
      DROP TABLE objects;
      ALTER TABLE objects_v4 RENAME TO objects;
      CREATE TABLE views_v4 (
        id INTEGER PRIMARY KEY,
        object_id INTEGER NOT NULL REFERENCES objects (id) ON DELETE CASCADE,
        azimuth REAL NOT NULL CHECK (azimuth >= 0 AND azimuth < 360),
        elevation REAL CHECK (elevation BETWEEN -90 AND 90),
        descriptor BLOB NOT NULL CHECK (length(descriptor) IN (144, 480)),
        typical_distance REAL NOT NULL CHECK (typical_distance BETWEEN 0 AND 1),
        thumbnail BLOB CHECK (length(thumbnail) <= 65536)
      ) STRICT;
      INSERT INTO views_v4 (id, object_id, azimuth, elevation, descriptor, typical_distance,
                            thumbnail)
        SELECT id, object_id, azimuth, elevation, descriptor, typical_distance, thumbnail
        FROM views;
      DROP TABLE views;
      ALTER TABLE views_v4 RENAME TO views;
      CREATE INDEX views_by_object ON views (object_id, azimuth);
    )sql",
    // 5: the cedd-hsv-layout variant, 480 bytes as cedd-hsv-hog. objects is rebuilt as in 3.
    R"sql(
      CREATE TABLE objects_v5 (
        id INTEGER PRIMARY KEY AUTOINCREMENT,
        name TEXT NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
        variant TEXT NOT NULL CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust',
                                                 'cedd-hsv-hog', 'cedd-hsv-layout')),
        created_at TEXT NOT NULL,
        updated_at TEXT NOT NULL,
        metadata TEXT NOT NULL DEFAULT '{}'
          CHECK (json_valid(metadata) AND json_type(metadata) = 'object')
      ) STRICT;
      INSERT INTO objects_v5 (id, name, variant, created_at, updated_at, metadata)
        SELECT id, name, variant, created_at, updated_at, metadata FROM objects;
      DELETE FROM sqlite_sequence WHERE name = 'objects_v5';
      INSERT INTO sqlite_sequence (name, seq)
        SELECT 'objects_v5', seq FROM sqlite_sequence WHERE name = 'objects';
      DROP TABLE objects;
      ALTER TABLE objects_v5 RENAME TO objects;
    )sql",
    // 6: the cedd-soft-hsv-hog variant, 480 bytes as cedd-hsv-hog. objects is rebuilt as in 3.
    R"sql(
      CREATE TABLE objects_v6 (
        id INTEGER PRIMARY KEY AUTOINCREMENT,
        name TEXT NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
        variant TEXT NOT NULL CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust',
                                                 'cedd-hsv-hog', 'cedd-hsv-layout',
                                                 'cedd-soft-hsv-hog')),
        created_at TEXT NOT NULL,
        updated_at TEXT NOT NULL,
        metadata TEXT NOT NULL DEFAULT '{}'
          CHECK (json_valid(metadata) AND json_type(metadata) = 'object')
      ) STRICT;
      INSERT INTO objects_v6 (id, name, variant, created_at, updated_at, metadata)
        SELECT id, name, variant, created_at, updated_at, metadata FROM objects;
      DELETE FROM sqlite_sequence WHERE name = 'objects_v6';
      INSERT INTO sqlite_sequence (name, seq)
        SELECT 'objects_v6', seq FROM sqlite_sequence WHERE name = 'objects';
      DROP TABLE objects;
      ALTER TABLE objects_v6 RENAME TO objects;
    )sql",
};
static_assert(std::size(kMigrations) == kSchemaVersion);

}  // namespace

int ReadSchemaVersion(SqliteConnection& connection) {
  const std::string has_version_table = connection.QueryText(
      "SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = 'schema_version'");
  if (has_version_table == "0") {
    if (connection.QueryText("SELECT count(*) FROM sqlite_schema") == "0") return 0;
    throw StoreError(StoreError::Code::kIncompatible,
                     connection.file().string() +
                         " is not an Orbit model store: it holds tables but no schema_version");
  }
  StatementLease version = connection.Prepare("SELECT max(version) FROM schema_version");
  if (!version->Step() || version->IsNull(0)) {
    throw StoreError(StoreError::Code::kIncompatible,
                     connection.file().string() +
                         " is not an Orbit model store: its schema_version table is empty");
  }
  return static_cast<int>(version->ColumnInt64(0));
}

namespace {

// Applies the missing migrations, one transaction each (foreign keys are off: MigrateSchema).
void ApplyMigrations(SqliteConnection& connection) {
  for (;;) {
    SqliteTransaction transaction(connection, SqliteTransaction::Mode::kWrite);
    const int version = ReadSchemaVersion(connection);
    if (version > kSchemaVersion) {
      throw StoreError(StoreError::Code::kIncompatible,
                       connection.file().string() + " has schema version " +
                           std::to_string(version) + ", newer than the versions 1.." +
                           std::to_string(kSchemaVersion) +
                           " this program knows: use a newer orbit");
    }
    if (version == kSchemaVersion) return;  // the read-only transaction just ends
    connection.Execute(kMigrations[version]);
    if (!connection.QueryText("PRAGMA foreign_key_check").empty()) {
      throw StoreError(StoreError::Code::kCorrupt,
                       connection.file().string() + ": migration to schema version " +
                           std::to_string(version + 1) + " found views of missing objects");
    }
    StatementLease record = connection.Prepare(
        "INSERT INTO schema_version (version, applied_at) "
        "VALUES (?1, strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))");
    record->Bind(1, static_cast<std::int64_t>(version + 1));
    record->Run();
    transaction.Commit();
  }
}

}  // namespace

void MigrateSchema(SqliteConnection& connection) {
  // The common case, an up-to-date store, needs no write lock.
  if (ReadSchemaVersion(connection) == kSchemaVersion) return;
  // A migration may rebuild a table that others reference (3): with foreign keys on, dropping
  // it would cascade. They are switched off for the migrations (a pragma that only takes
  // effect outside a transaction), checked before each commit, and restored however we leave.
  const bool foreign_keys = connection.QueryText("PRAGMA foreign_keys") == "1";
  connection.Execute("PRAGMA foreign_keys = OFF");
  try {
    ApplyMigrations(connection);
  } catch (...) {
    if (foreign_keys) connection.Execute("PRAGMA foreign_keys = ON");
    throw;
  }
  if (foreign_keys) connection.Execute("PRAGMA foreign_keys = ON");
}

}  // namespace orbit
