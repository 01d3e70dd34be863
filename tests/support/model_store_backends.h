// The two ModelStore implementations behind one face, so that the tests of ModelStore's
// contracts (tests/storage/model_store_test.cc) run once on each: a typed GoogleTest suite over
// SqliteBackend and PostgresBackend. A backend owns the place its store lives (a scratch file, a
// fresh database), opens as many stores on it as a test asks for, and counts rows from outside
// the store.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "storage/postgres_model_store.h"
#include "storage/sqlite_model_store.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"

namespace orbit::testing {

struct SqliteBackend {
  static constexpr const char* kName = "Sqlite";

  std::unique_ptr<ModelStore> Open() const {
    return std::make_unique<SqliteModelStore>(dir / "models.db",
                                              SqliteModelStoreOptions{.create_if_missing = true});
  }
  // The single number `sql` returns, read beside the store.
  std::int64_t Int(const std::string& sql) const { return RawDatabase(dir / "models.db").Int(sql); }

  ScratchDir dir;
};

struct PostgresBackend {
  static constexpr const char* kName = "Postgres";

  std::unique_ptr<ModelStore> Open() const {
    return std::make_unique<PostgresModelStore>(database.conninfo());
  }
  std::int64_t Int(const std::string& sql) const { return database.Int(sql); }

  TestDatabase database;
};

// Test names carry the backend's name ("ModelStoreTest/Postgres.Rename..."): ctest gives the
// *Postgres* ones their server (tests/CMakeLists.txt).
struct BackendName {
  template <typename Backend>
  static std::string GetName(int) {
    return Backend::kName;
  }
};

}  // namespace orbit::testing
