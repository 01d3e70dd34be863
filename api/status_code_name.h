// The canonical names of gRPC status codes ("OK", "INVALID_ARGUMENT", ...), written once for the
// client library's errors, the server's metrics labels and `orbit loadtest`'s reports.
#pragma once

#include <string_view>

#include <grpcpp/support/status.h>

namespace orbit {

// The canonical name of `code`, as gRPC's documentation spells it; "UNKNOWN_CODE" for a value
// outside the 17 codes.
std::string_view StatusCodeName(grpc::StatusCode code);

}  // namespace orbit
