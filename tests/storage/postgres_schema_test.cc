// The PostgreSQL store's schema: created in an empty database, left alone when current, applied
// once when replicas start together, and refused when it is newer or another application's.
#include "storage/postgres_schema.h"

#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/postgres_model_store.h"
#include "storage/store_error.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::StoreErrorOf;
using testing::SyntheticObject;
using testing::TestDatabase;

TEST(PostgresSchemaTest, ReplicasOpeningAnEmptyDatabaseTogetherCreateTheSchemaOnce) {
  TestDatabase database;
  std::vector<std::thread> replicas;
  for (int i = 0; i < 4; ++i) {
    replicas.emplace_back([&] { PostgresModelStore store(database.conninfo()); });
  }
  for (std::thread& replica : replicas) replica.join();

  EXPECT_EQ(database.Int("SELECT count(*) FROM schema_version"), kPostgresSchemaVersion);
  EXPECT_EQ(database.Int("SELECT max(version) FROM schema_version"), kPostgresSchemaVersion);
  PostgresConnection connection(database.conninfo(), 0);
  EXPECT_EQ(ReadPostgresSchemaVersion(connection), kPostgresSchemaVersion);
}

TEST(PostgresSchemaTest, AStoreInItsOwnSchemaSharesADatabaseWithOtherTables) {
  TestDatabase database;
  database.Execute("CREATE TABLE invoices (id int); CREATE SCHEMA models");

  const auto [code, message] = StoreErrorOf([&] { PostgresModelStore store(database.conninfo()); });
  EXPECT_EQ(code, StoreError::Code::kIncompatible);
  EXPECT_THAT(message, HasSubstr("is not an Orbit model store"));
  EXPECT_THAT(message, HasSubstr("search_path"));

  PostgresModelStore store(database.conninfo() + " options=-csearch_path=models");
  store.Enroll(SyntheticObject("mug", 2));
  EXPECT_EQ(database.Int("SELECT count(*) FROM models.objects"), 1);
  EXPECT_EQ(database.Int("SELECT count(*) FROM invoices"), 0);
}

TEST(PostgresSchemaTest, ANewerSchemaIsRefusedAndLeftUntouched) {
  TestDatabase database;
  { PostgresModelStore store(database.conninfo()); }
  database.Execute("INSERT INTO schema_version (version) VALUES (" +
                   std::to_string(kPostgresSchemaVersion + 1) + ")");

  const auto [code, message] = StoreErrorOf([&] { PostgresModelStore store(database.conninfo()); });
  EXPECT_EQ(code, StoreError::Code::kIncompatible);
  EXPECT_THAT(message,
              HasSubstr("newer than the versions 1.." + std::to_string(kPostgresSchemaVersion)));
  EXPECT_EQ(database.Int("SELECT count(*) FROM schema_version"), kPostgresSchemaVersion + 1);
}

}  // namespace
}  // namespace orbit
