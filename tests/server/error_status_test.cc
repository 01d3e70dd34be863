// The one mapping of errors to gRPC statuses (server/error_status.h).
#include "server/error_status.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "storage/store_error.h"

namespace orbit::server {
namespace {

TEST(ErrorStatusTest, EachErrorGetsItsCodeAndKeepsItsMessage) {
  using Code = StoreError::Code;
  const struct {
    Code code;
    grpc::StatusCode status;
  } store_cases[] = {
      {Code::kNotFound, grpc::StatusCode::NOT_FOUND},
      {Code::kAlreadyExists, grpc::StatusCode::ALREADY_EXISTS},
      {Code::kFull, grpc::StatusCode::RESOURCE_EXHAUSTED},
      {Code::kBusy, grpc::StatusCode::UNAVAILABLE},
      {Code::kCorrupt, grpc::StatusCode::INTERNAL},
      {Code::kIo, grpc::StatusCode::UNAVAILABLE},
  };
  for (const auto& c : store_cases) {
    const grpc::Status status = StatusFromException(StoreError(c.code, "store says so"));
    EXPECT_EQ(status.error_code(), c.status);
    EXPECT_EQ(status.error_message(), "store says so");
  }
  const grpc::Status invalid = StatusFromException(std::invalid_argument("window must be 1..64"));
  EXPECT_EQ(invalid.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(invalid.error_message(), "window must be 1..64");
  EXPECT_EQ(StatusFromException(std::runtime_error("disk on fire")).error_code(),
            grpc::StatusCode::INTERNAL);
  EXPECT_EQ(InvalidArgument("x").error_code(), grpc::StatusCode::INVALID_ARGUMENT);
}

}  // namespace
}  // namespace orbit::server
