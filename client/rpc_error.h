// RpcError: how the client library reports a call the server (or the network) refused.
//
// Every call of the client library (Connection, ModelsClient, Enroller, RecognitionSession)
// throws RpcError for a non-OK gRPC status, carrying the code and the server's message
// unchanged, so a caller can tell UNAUTHENTICATED from NOT_FOUND from UNAVAILABLE
// (docs/design.md#service-behaviour lists which status each bad input gets). Arguments the library
// itself can reject before any call (an empty image, a bad region) throw std::invalid_argument,
// as core/ does.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <grpcpp/support/status.h>

namespace orbit {

class RpcError : public std::runtime_error {
 public:
  // `what` is "<call>: <CODE_NAME>: <message>", e.g. "DeleteObject: NOT_FOUND: no object 7".
  RpcError(std::string_view call, const grpc::Status& status);

  grpc::StatusCode code() const { return status_.error_code(); }
  const grpc::Status& status() const { return status_; }

 private:
  grpc::Status status_;
};

// Throws RpcError(call, status) unless status is OK.
void ThrowIfError(std::string_view call, const grpc::Status& status);

}  // namespace orbit
