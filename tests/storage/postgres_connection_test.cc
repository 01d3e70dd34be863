// PostgresConnection: what an operator is shown of a connection string, and values that travel
// to the server and back unchanged.
#include "storage/postgres_connection.h"

#include <cmath>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/postgres_test_cluster.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;

TEST(PostgresConnectionTest, RedactedTargetKeepsEverythingButThePassword) {
  EXPECT_EQ(RedactedTarget("postgresql://orbit:s3cret@db.example:6543/models?sslmode=require"),
            "user=orbit dbname=models host=db.example port=6543 sslmode=require");
  EXPECT_EQ(RedactedTarget("host=/run/postgresql dbname=models password=s3cret"),
            "dbname=models host=/run/postgresql");
  try {
    RedactedTarget("host=db.example dbname");
    ADD_FAILURE() << "a malformed connection string was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("invalid PostgreSQL connection string"));
    EXPECT_THAT(e.what(), HasSubstr("dbname"));
  }
}

TEST(PostgresConnectionTest, ValuesComeBackFromTheServerExactly) {
  testing::TestDatabase database;
  PostgresConnection connection(database.conninfo(), 0);
  const std::string bytes("\0\x01\xff\\x'", 6);
  const PostgresResult row = connection.Query(
      "SELECT $1::bigint, $2::float8, $3::float8, $4::text, $5::bytea, $6::text IS NULL",
      PostgresParams()
          .Add(std::int64_t{-9007199254740993})
          .Add(0.1)
          .Add(std::nextafter(360.0, 0.0))
          .Add(std::string_view("naïve 'quoted'"))
          .AddBytes({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()})
          .AddNull());
  ASSERT_EQ(row.rows(), 1);
  EXPECT_EQ(row.Int64(0, 0), -9007199254740993);
  EXPECT_EQ(row.Double(0, 1), 0.1);
  EXPECT_EQ(row.Double(0, 2), std::nextafter(360.0, 0.0));
  EXPECT_EQ(row.Text(0, 3), "naïve 'quoted'");
  EXPECT_EQ(row.Bytes(0, 4), bytes);
  EXPECT_EQ(row.Text(0, 5), "t");
}

}  // namespace
}  // namespace orbit
