// The PostgreSQL model store's schema and its migrations (docs/storage.md, "PostgreSQL store").
//
// Like the SQLite store's (storage/schema.h): the database records its schema version in the
// table `schema_version`, one row per migration applied, and the program knows versions
// 1..kPostgresSchemaVersion. All missing migrations run in one transaction that holds the store's
// write lock (storage/postgres_transaction.h) and re-reads the version first, so replicas starting
// together apply each migration exactly once, and a failure leaves the previous version whole
// (PostgreSQL's schema changes are transactional).
//
// The tables live in the connection's current schema (the first of its search_path), so one
// database can hold several stores in schemas of their own.
#pragma once

#include "storage/postgres_connection.h"

namespace orbit {

// Version 1: objects, views (as the SQLite store's version 3) and the change log model_changes.
// Version 2: the cedd-hsv-hog variant. Version 3: replica_progress and change_log_horizon, for
// pruning the change log. Version 4: the cedd-hsv-layout variant. Version 5: the
// cedd-soft-hsv-hog variant.
inline constexpr int kPostgresSchemaVersion = 5;

// The schema version of the store on `connection`: 0 when the current schema has no tables.
// Throws StoreError kIncompatible when it has tables but is not an Orbit model store.
int ReadPostgresSchemaVersion(PostgresConnection& connection);

// Brings the store to kPostgresSchemaVersion. Throws StoreError kIncompatible, changing nothing,
// when the store is newer than kPostgresSchemaVersion or the schema holds other tables.
void MigratePostgresSchema(PostgresConnection& connection);

}  // namespace orbit
