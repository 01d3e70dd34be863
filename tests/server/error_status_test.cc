// The one mapping of errors to gRPC statuses (server/error_status.h).
#include "server/error_status.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "storage/store_error.h"

namespace orbit::server {
namespace {

TEST(ErrorStatusTest, EachErrorGetsItsCodeAndTheClientNeverTheStoresOwnWords) {
  using Code = StoreError::Code;
  const std::string store_words = "`INSERT INTO objects ...` on /var/lib/orbit/models.db: CHECK";
  const struct {
    Code code;
    grpc::StatusCode status;
    std::string message;
  } store_cases[] = {
      {Code::kNotFound, grpc::StatusCode::NOT_FOUND, store_words},
      {Code::kAlreadyExists, grpc::StatusCode::ALREADY_EXISTS, store_words},
      {Code::kConstraint, grpc::StatusCode::INVALID_ARGUMENT,
       "the model store refused the values of this request; nothing was stored"},
      {Code::kFull, grpc::StatusCode::RESOURCE_EXHAUSTED,
       "the model store is full; nothing was stored"},
      {Code::kBusy, grpc::StatusCode::UNAVAILABLE,
       "the model store is busy; retry later or on another replica"},
      {Code::kCorrupt, grpc::StatusCode::INTERNAL,
       "the model store failed; the server's log says why"},
      {Code::kIo, grpc::StatusCode::UNAVAILABLE,
       "the model store cannot be reached or written; retry later or on another replica"},
  };
  for (const auto& c : store_cases) {
    const grpc::Status status = StatusFromException(StoreError(c.code, store_words));
    EXPECT_EQ(status.error_code(), c.status);
    EXPECT_EQ(status.error_message(), c.message);
  }
  EXPECT_EQ(RefusalReasonOf(StoreError(Code::kConstraint, store_words)),
            RefusalReason::kInvalidField);
  EXPECT_EQ(RefusalReasonOf(StoreError(Code::kBusy, store_words)), RefusalReason::kStore);
  const grpc::Status invalid = StatusFromException(std::invalid_argument("window must be 1..64"));
  EXPECT_EQ(invalid.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(invalid.error_message(), "window must be 1..64");
  EXPECT_EQ(StatusFromException(std::runtime_error("disk on fire")).error_code(),
            grpc::StatusCode::INTERNAL);
  EXPECT_EQ(InvalidArgument("x").error_code(), grpc::StatusCode::INVALID_ARGUMENT);
}

}  // namespace
}  // namespace orbit::server
