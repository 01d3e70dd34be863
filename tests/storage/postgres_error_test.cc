// What each PostgreSQL failure means for the caller (the codes server/ maps to gRPC statuses).
#include "storage/postgres_error.h"

#include <gtest/gtest.h>

namespace orbit {
namespace {

using Code = StoreError::Code;

TEST(PostgresErrorTest, SqlStatesMapToWhatACallerCanDo) {
  EXPECT_EQ(PostgresError("23505", "", "").code(), Code::kAlreadyExists);  // unique_violation
  EXPECT_EQ(PostgresError("23514", "", "").code(), Code::kConstraint);     // check_violation
  EXPECT_EQ(PostgresError("22P02", "", "").code(), Code::kConstraint);     // bad json text
  EXPECT_EQ(PostgresError("55P03", "", "").code(), Code::kBusy);           // lock_timeout
  EXPECT_EQ(PostgresError("40001", "", "").code(), Code::kBusy);           // serialization
  EXPECT_EQ(PostgresError("53100", "", "").code(), Code::kFull);           // disk_full
  EXPECT_EQ(PostgresError("XX001", "", "").code(), Code::kCorrupt);        // data_corrupted
  EXPECT_EQ(PostgresError("08006", "", "").code(), Code::kIo);             // connection_failure
  EXPECT_EQ(PostgresError("57P01", "", "").code(), Code::kIo);             // admin_shutdown
  EXPECT_EQ(PostgresError("", "", "").code(), Code::kIo);                  // no answer at all
  EXPECT_EQ(PostgresError("42P01", "", "").code(), Code::kInternal);       // undefined_table
}

TEST(PostgresErrorTest, TheMessageIsTheContextThenTheServersWords) {
  EXPECT_STREQ(
      PostgresError("23514", "ERROR:  injected failure\n", "PostgreSQL refused `INSERT`").what(),
      "PostgreSQL refused `INSERT`: ERROR:  injected failure");
}

}  // namespace
}  // namespace orbit
