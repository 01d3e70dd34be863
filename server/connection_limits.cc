#include "server/connection_limits.h"

#include <stdexcept>
#include <string>

#include <grpc/grpc.h>
#include <grpcpp/resource_quota.h>

#include "server/connection_admission.h"

namespace orbit::server {
namespace {

constexpr int kMillisecondsPerSecond = 1000;

void CheckRange(int value, int low, int high, const char* flag) {
  if (value < low || value > high) {
    throw std::invalid_argument(std::string(flag) + " is " + std::to_string(value) + ", expected " +
                                std::to_string(low) + ".." + std::to_string(high));
  }
}

}  // namespace

void ValidateConnectionLimits(const ConnectionLimits& limits) {
  constexpr int kDay = 86400;
  CheckRange(limits.descriptor_reserve, 8, 65536, "--descriptor-reserve");
  CheckRange(limits.handshake_timeout_seconds, 1, 3600, "--handshake-timeout");
  CheckRange(limits.idle_timeout_seconds, 1, kDay, "--connection-idle-timeout");
  CheckRange(limits.max_age_seconds, 0, kDay, "--connection-max-age");
  CheckRange(limits.age_grace_seconds, 0, kDay, "--connection-age-grace");
  CheckRange(limits.keepalive_seconds, 1, kDay, "--keepalive");
  CheckRange(limits.keepalive_timeout_seconds, 1, 3600, "--keepalive-timeout");
  CheckRange(limits.max_streams_per_connection, 1, 100000, "--max-streams-per-connection");
  CheckRange(limits.memory_mib, 16, 1 << 20, "--connection-memory");
}

void ApplyConnectionLimits(const ConnectionLimits& limits, grpc::ServerBuilder& builder) {
  const auto ms = [](int seconds) { return seconds * kMillisecondsPerSecond; };
  builder.AddChannelArgument(GRPC_ARG_SERVER_HANDSHAKE_TIMEOUT_MS,
                             ms(limits.handshake_timeout_seconds));
  builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_IDLE_MS, ms(limits.idle_timeout_seconds));
  if (limits.max_age_seconds > 0) {
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_MS, ms(limits.max_age_seconds));
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS, ms(limits.age_grace_seconds));
  }
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, ms(limits.keepalive_seconds));
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, ms(limits.keepalive_timeout_seconds));
  // Pings keep a connection alive only while it carries a call; a client pinging an idle one
  // more often than every 10 s is answered with GOAWAY (gRPC's ping-strike rule).
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 0);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS,
                             10 * kMillisecondsPerSecond);
  builder.AddChannelArgument(GRPC_ARG_MAX_CONCURRENT_STREAMS, limits.max_streams_per_connection);
  grpc::ResourceQuota quota("orbit-connections");
  quota.Resize(static_cast<std::size_t>(limits.memory_mib) << 20);
  builder.SetResourceQuota(quota);
  AdmitConnectionsKeepingFree(limits.descriptor_reserve);
}

}  // namespace orbit::server
