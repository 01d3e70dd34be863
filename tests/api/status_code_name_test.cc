// Status code names (api/status_code_name.h): the names gRPC's documentation gives its 17 codes,
// which users see in the client library's errors, the metrics' `code` label and load reports.
#include "api/status_code_name.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(StatusCodeNameTest, EveryCodeHasItsCanonicalName) {
  // In the numeric order of grpc/status.h, checked against
  // grpc.github.io/grpc/core/md_doc_statuscodes.
  const char* const expected[] = {"OK",
                                  "CANCELLED",
                                  "UNKNOWN",
                                  "INVALID_ARGUMENT",
                                  "DEADLINE_EXCEEDED",
                                  "NOT_FOUND",
                                  "ALREADY_EXISTS",
                                  "PERMISSION_DENIED",
                                  "RESOURCE_EXHAUSTED",
                                  "FAILED_PRECONDITION",
                                  "ABORTED",
                                  "OUT_OF_RANGE",
                                  "UNIMPLEMENTED",
                                  "INTERNAL",
                                  "UNAVAILABLE",
                                  "DATA_LOSS",
                                  "UNAUTHENTICATED"};
  std::set<std::string> names;
  for (int code = 0; code < 17; ++code) {
    const std::string name(StatusCodeName(static_cast<grpc::StatusCode>(code)));
    EXPECT_EQ(name, expected[code]) << "code " << code;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), 17u);
}

TEST(StatusCodeNameTest, AValueOutsideTheCodesIsNamedAsSuch) {
  EXPECT_EQ(StatusCodeName(static_cast<grpc::StatusCode>(17)), "UNKNOWN_CODE");
  EXPECT_EQ(StatusCodeName(static_cast<grpc::StatusCode>(-1)), "UNKNOWN_CODE");
}

}  // namespace
}  // namespace orbit
