// The model store's schema and its migrations (docs/storage.md has the tables and the why).
//
// The database records its schema version in the table `schema_version`, one row per migration
// applied. The program knows versions 1..kSchemaVersion; each migration runs in one IMMEDIATE
// transaction that re-reads the version first, so two processes opening an old store at once
// apply each migration exactly once, and a crash mid-migration leaves the previous version whole.
#pragma once

#include "storage/sqlite_connection.h"

namespace orbit {

// Version 1: objects and views (the recognition data). Version 2: objects.metadata (JSON text)
// and views.thumbnail. Version 3: objects.variant may be cedd-robust. Version 4: cedd-hsv-hog, and
// views.descriptor 144 or 480 bytes. Version 5: cedd-hsv-layout. Version 6: cedd-soft-hsv-hog.
inline constexpr int kSchemaVersion = 6;

// The schema version of the database on `connection`: 0 for an empty database.
// Throws StoreError kIncompatible when the database has tables but is not an Orbit model store.
int ReadSchemaVersion(SqliteConnection& connection);

// Brings the database to kSchemaVersion, one transaction per migration. Throws StoreError
// kIncompatible, changing nothing, when the database is newer than kSchemaVersion or is not an
// Orbit model store.
void MigrateSchema(SqliteConnection& connection);

}  // namespace orbit
