// Calls in progress per token (server/calls_per_token.h).
#include "server/calls_per_token.h"

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

TEST(CallsPerTokenTest, HoldsEachTokenToItsLimitAndFreesOnRelease) {
  CallsPerToken calls(2, "--max-recognize-calls-per-token");
  EXPECT_TRUE(calls.Acquire("phone").ok());
  EXPECT_TRUE(calls.Acquire("phone").ok());
  const grpc::Status refused = calls.Acquire("phone");
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(refused.error_message(),
            "this token already has 2 calls in progress (--max-recognize-calls-per-token); wait "
            "for one to end");
  EXPECT_TRUE(calls.Acquire("drone").ok()) << "another token's calls are its own";
  calls.Release("phone");
  EXPECT_TRUE(calls.Acquire("phone").ok());
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(calls.Acquire("").ok()) << "no token: not counted";
}

TEST(CallsPerTokenTest, ZeroMeansNoLimit) {
  CallsPerToken calls(0, "--max-recognize-calls-per-token");
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(calls.Acquire("phone").ok());
}

}  // namespace
}  // namespace orbit::server
