// Raw TCP connections to a server, opened the way a hostile client opens them: no gRPC, nothing
// but (optionally) the HTTP/2 client preface and an empty SETTINGS frame, then silence.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace orbit::testing {

// What a raw connection sends after connecting.
enum class RawGreeting {
  kNothing,         // not even the preface: a connection stuck before its handshake
  kPrefaceSettings  // "PRI * HTTP/2.0..." and an empty SETTINGS frame: an HTTP/2 client with no
                    // call
};

// Open connections to a loopback port, closed by the destructor (or Close).
class RawConnections {
 public:
  // Connects `count` times to 127.0.0.1:`port`, sending `greeting` on each. A connect the server
  // refuses or resets is not kept: connected() says how many were.
  RawConnections(int port, int count, RawGreeting greeting);
  ~RawConnections() { Close(); }

  RawConnections(const RawConnections&) = delete;
  RawConnections& operator=(const RawConnections&) = delete;

  int connected() const { return static_cast<int>(sockets_.size()); }

  // How many of the connections the server has closed (end of stream or reset) within
  // `timeout`, waiting until all are or the time is up. What the server sent before closing
  // (its SETTINGS, a GOAWAY) is read and dropped.
  int ClosedByServerWithin(std::chrono::milliseconds timeout);

  void Close();

 private:
  std::vector<int> sockets_;
};

}  // namespace orbit::testing
