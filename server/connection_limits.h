// ConnectionLimits: what one TCP connection may hold of the server, and for how long
// (docs/design.md#connection-admission; each limit's flag and default: docs/service.md, "Limits").
// A connection that sends nothing, or holds no call, is closed after a bounded time, so that
// connections a client leaves open, or a flood holds, give their descriptors and memory back.
#pragma once

#include <grpcpp/server_builder.h>

namespace orbit::server {

struct ConnectionLimits {
  // Descriptors kept free for the store, the logs and the metrics: a connection that would use
  // one is closed as soon as it is accepted (server/connection_admission.h).
  int descriptor_reserve = 64;
  // From accepting a connection to its first HTTP/2 settings (TLS handshake included).
  int handshake_timeout_seconds = 10;
  // A connection with no call open for this long is sent GOAWAY and closed; a client's channel
  // reconnects at its next call. Sessions and enrollments are calls, so they are never idle.
  int idle_timeout_seconds = 60;
  // 0: none. Else a connection is sent GOAWAY after this long and its calls get
  // age_grace_seconds to end, so that clients spread again over a balancer's servers.
  int max_age_seconds = 0;
  int age_grace_seconds = 30;
  // The server pings a connection quiet for this long and closes it when no answer comes
  // within keepalive_timeout_seconds: a device that vanished without closing gives back its
  // connection and the sessions on it.
  int keepalive_seconds = 60;
  int keepalive_timeout_seconds = 20;
  int max_streams_per_connection = 100;  // calls open at once on one connection
  // What gRPC's buffers of every connection together may hold (its resource quota), in MiB;
  // above it, new connections are dropped and reads are slowed.
  int memory_mib = 1024;
};

// Sets `limits` on `builder` (gRPC channel arguments and resource quota) and starts admitting
// connections with limits.descriptor_reserve free. REQUIRES: limits checked by
// ValidateConnectionLimits.
void ApplyConnectionLimits(const ConnectionLimits& limits, grpc::ServerBuilder& builder);

// Throws std::invalid_argument naming the flag of a value out of range.
void ValidateConnectionLimits(const ConnectionLimits& limits);

}  // namespace orbit::server
