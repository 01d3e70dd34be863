#include "storage/postgres_schema.h"

#include <iterator>
#include <string>

#include "storage/postgres_transaction.h"
#include "storage/store_error.h"

namespace orbit {
namespace {

// migrations[v - 1] takes the schema from version v - 1 to v. Never edit a shipped migration:
// databases in the field were built by it; add a new one instead.
constexpr const char* kMigrations[] = {
    // 1: the recognition data, as the SQLite store's schema 3, and the change log.
    // Identity columns never hand out a value twice (sequences do not roll back), so the id of a
    // deleted object is never reused. metadata is `json`, which keeps the text as given. The
    // CHECKs are the last line behind storage/model_validation.h.
    // model_changes: one row per write, in the write's own transaction; seq is in commit order
    // because every write holds the store's write lock until it commits. It keeps the ids of
    // deleted objects, so it has no foreign key.
    R"sql(
      CREATE TABLE schema_version (
        version integer PRIMARY KEY,
        applied_at timestamptz NOT NULL DEFAULT now()
      );
      CREATE TABLE objects (
        id bigint GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
        name text NOT NULL UNIQUE CHECK (length(name) BETWEEN 1 AND 64),
        variant text NOT NULL CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust')),
        created_at timestamptz NOT NULL,
        updated_at timestamptz NOT NULL,
        metadata json NOT NULL DEFAULT '{}' CHECK (json_typeof(metadata) = 'object')
      );
      CREATE TABLE views (
        id bigint GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
        object_id bigint NOT NULL REFERENCES objects (id) ON DELETE CASCADE,
        azimuth double precision NOT NULL CHECK (azimuth >= 0 AND azimuth < 360),
        elevation double precision CHECK (elevation BETWEEN -90 AND 90),
        descriptor bytea NOT NULL CHECK (length(descriptor) = 144),
        typical_distance double precision NOT NULL CHECK (typical_distance BETWEEN 0 AND 1),
        thumbnail bytea CHECK (length(thumbnail) <= 65536)
      );
      CREATE INDEX views_by_object ON views (object_id, azimuth);
      CREATE TABLE model_changes (
        seq bigint GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
        object_id bigint NOT NULL,
        kind text NOT NULL CHECK (kind IN ('enroll', 'add_views', 'delete', 'rename')),
        committed_at timestamptz NOT NULL DEFAULT clock_timestamp()
      );
    )sql",
    // 2: the cedd-hsv-hog variant, whose descriptors are 480 bytes.
    R"sql(
      ALTER TABLE objects DROP CONSTRAINT objects_variant_check,
        ADD CONSTRAINT objects_variant_check
          CHECK (variant IN ('cedd-lire', 'cedd-full', 'cedd-robust', 'cedd-hsv-hog'));
      ALTER TABLE views DROP CONSTRAINT views_descriptor_check,
        ADD CONSTRAINT views_descriptor_check CHECK (length(descriptor) IN (144, 480));
    )sql",
    // 3: pruning the change log (docs/design.md#change-log). replica_progress: the last change
    // each replica has applied, stamped by the database's clock (replicas' clocks may disagree).
    // change_log_horizon: one row, the seq through which changes may have been deleted.
    R"sql(
      CREATE TABLE replica_progress (
        replica text PRIMARY KEY,
        applied_seq bigint NOT NULL,
        reported_at timestamptz NOT NULL
      );
      CREATE TABLE change_log_horizon (
        one_row boolean PRIMARY KEY DEFAULT true CHECK (one_row),
        pruned_through bigint NOT NULL
      );
      INSERT INTO change_log_horizon (pruned_through) VALUES (0);
    )sql",
    // 4: the cedd-hsv-layout variant, 480 bytes as cedd-hsv-hog.
    R"sql(
      ALTER TABLE objects DROP CONSTRAINT objects_variant_check,
        ADD CONSTRAINT objects_variant_check CHECK (variant IN ('cedd-lire', 'cedd-full',
          'cedd-robust', 'cedd-hsv-hog', 'cedd-hsv-layout'));
    )sql",
    // 5: the cedd-soft-hsv-hog variant, 480 bytes as cedd-hsv-hog.
    R"sql(
      ALTER TABLE objects DROP CONSTRAINT objects_variant_check,
        ADD CONSTRAINT objects_variant_check CHECK (variant IN ('cedd-lire', 'cedd-full',
          'cedd-robust', 'cedd-hsv-hog', 'cedd-hsv-layout', 'cedd-soft-hsv-hog'));
    )sql",
};
static_assert(std::size(kMigrations) == kPostgresSchemaVersion);

}  // namespace

int ReadPostgresSchemaVersion(PostgresConnection& connection) {
  const PostgresResult tables = connection.Query(
      "SELECT count(*), count(*) FILTER (WHERE tablename = 'schema_version') FROM pg_tables "
      "WHERE schemaname = current_schema()");
  if (tables.Int64(0, 1) == 0) {
    if (tables.Int64(0, 0) == 0) return 0;
    throw StoreError(StoreError::Code::kIncompatible,
                     "PostgreSQL " + connection.target() +
                         " is not an Orbit model store: its schema holds tables but no "
                         "schema_version (give the store a schema of its own: "
                         "options=-csearch_path=NAME)");
  }
  const PostgresResult version = connection.Query("SELECT max(version) FROM schema_version");
  if (version.IsNull(0, 0)) {
    throw StoreError(StoreError::Code::kIncompatible,
                     "PostgreSQL " + connection.target() +
                         " is not an Orbit model store: its schema_version table is empty");
  }
  return static_cast<int>(version.Int64(0, 0));
}

void MigratePostgresSchema(PostgresConnection& connection) {
  // The common case, an up-to-date store, needs no lock.
  if (ReadPostgresSchemaVersion(connection) == kPostgresSchemaVersion) return;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  const int version = ReadPostgresSchemaVersion(connection);
  if (version > kPostgresSchemaVersion) {
    throw StoreError(StoreError::Code::kIncompatible,
                     "PostgreSQL " + connection.target() + " has schema version " +
                         std::to_string(version) + ", newer than the versions 1.." +
                         std::to_string(kPostgresSchemaVersion) +
                         " this program knows: use a newer orbit");
  }
  for (int next = version + 1; next <= kPostgresSchemaVersion; ++next) {
    connection.Execute(kMigrations[next - 1]);
    connection.Query("INSERT INTO schema_version (version) VALUES ($1)",
                     PostgresParams().Add(std::int64_t{next}));
  }
  transaction.Commit();
}

}  // namespace orbit
