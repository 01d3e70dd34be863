// Connection: a channel to an Orbit server and how every call on it is made: plain or TLS,
// the bearer token each call carries, the deadline of unary calls.
//
// Thread-safe: a Connection is immutable once built and may be shared by any number of
// sessions, enrollers and model clients on any threads (gRPC channels multiplex calls).
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include <grpcpp/channel.h>
#include <grpcpp/client_context.h>

namespace orbit {

struct ConnectionOptions {
  std::string address;  // HOST:PORT of the server, e.g. "edge.local:50051" or "127.0.0.1:50051"
  // Bearer token sent as `authorization: Bearer <token>` metadata with every call; empty for a
  // server without tokens. Sent as metadata rather than call credentials so that it also
  // reaches a plaintext loopback server.
  std::string token;
  // PEM file of the root certificate(s) that signed the server's certificate. Empty: plaintext
  // (only sensible on loopback or a trusted network).
  std::string tls_root_certificates_file;
  // With TLS: the name the server's certificate must carry when it differs from the host in
  // `address` (e.g. connecting to 127.0.0.1 with a certificate for "orbit.local").
  std::string tls_server_name;
  // Deadline of every unary call (ServerInfo, ListObjects, Enroll, ...). Streaming sessions
  // have none: they last as long as the device streams.
  std::chrono::milliseconds unary_deadline{10000};
  // false: the channel shares its TCP connection with every other channel of this process to
  // the same address and options (gRPC's global subchannel pool); true: it opens a connection of
  // its own, as a separate device would (orbit loadtest --connections).
  bool own_connection = false;
};

class Connection {
 public:
  // Builds the channel; it connects lazily, on the first call. The reconnection backoff is
  // kept short (0.1 s, growing to at most 2 s) so a session resumes soon after a server restart.
  // Throws std::invalid_argument when the address is empty and std::runtime_error when the
  // root certificate file cannot be read.
  explicit Connection(ConnectionOptions options);

  const ConnectionOptions& options() const { return options_; }
  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }

  // Prepares `context` for a unary call: the token and a deadline of options().unary_deadline
  // from now.
  void PrepareUnaryCall(grpc::ClientContext& context) const;

  // Prepares `context` for a streaming call: the token only, no deadline.
  void PrepareStreamingCall(grpc::ClientContext& context) const;

  // Waits until the channel is connected or `timeout` passes; true when connected. Used before
  // reopening a session after the connection dropped.
  bool WaitForConnected(std::chrono::milliseconds timeout) const;

 private:
  ConnectionOptions options_;
  std::shared_ptr<grpc::Channel> channel_;
};

// Reads a token file as `orbit --token-file` does: the first non-empty line that is not a
// '#' comment, trimmed; its first word when the line also names a role ("<token> <role>", the
// server's tokens-file format). Throws std::runtime_error naming the file when it cannot be
// read or holds no token.
std::string ReadTokenFile(const std::string& path);

}  // namespace orbit
