// The grpc.health.v1 status a server reports, asked the way a balancer or an orchestrator asks
// (Health/Check), for the tests of readiness. Debian's gRPC ships no C++ stubs of the health
// proto, so the call goes through the generic stub with the message's two bytes written out.
#pragma once

#include <chrono>
#include <future>
#include <optional>
#include <string>

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

namespace orbit::testing {

// HealthCheckResponse.ServingStatus values.
inline constexpr int kServing = 1;
inline constexpr int kNotServing = 2;

// The status `address` reports for `service` ("" for the whole server); nullopt when the call
// fails (nothing listening, a status other than OK).
inline std::optional<int> HealthStatus(const std::string& address,
                                       const std::string& service = "") {
  const auto channel = grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  grpc::GenericStub stub(channel);
  std::string request;  // HealthCheckRequest: field 1 (service), a string
  if (!service.empty()) {
    request = std::string("\x0a", 1) + static_cast<char>(service.size()) + service;
  }
  grpc::Slice slice(request);
  grpc::ByteBuffer request_buffer(&slice, 1);
  grpc::ByteBuffer response_buffer;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
  std::promise<grpc::Status> done;
  stub.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request_buffer,
                 &response_buffer, [&done](grpc::Status status) { done.set_value(status); });
  if (!done.get_future().get().ok()) return std::nullopt;
  grpc::Slice reply;
  if (!response_buffer.DumpToSingleSlice(&reply).ok()) return std::nullopt;
  const std::string bytes(reinterpret_cast<const char*>(reply.begin()), reply.size());
  // HealthCheckResponse: field 1 (status), a varint; absent means UNKNOWN (0).
  if (bytes.size() == 2 && bytes[0] == '\x08') return bytes[1];
  return bytes.empty() ? std::optional<int>(0) : std::nullopt;
}

}  // namespace orbit::testing
