#include "client/rpc_error.h"

#include "api/status_code_name.h"

namespace orbit {
namespace {

std::string Describe(std::string_view call, const grpc::Status& status) {
  std::string text(call);
  text += ": ";
  text += StatusCodeName(status.error_code());
  if (!status.error_message().empty()) {
    text += ": ";
    text += status.error_message();
  }
  return text;
}

}  // namespace

RpcError::RpcError(std::string_view call, const grpc::Status& status)
    : std::runtime_error(Describe(call, status)), status_(status) {}

void ThrowIfError(std::string_view call, const grpc::Status& status) {
  if (!status.ok()) throw RpcError(call, status);
}

}  // namespace orbit
