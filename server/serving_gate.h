// ServingGate: whether the server has loaded its model index and may answer Orbit calls. The
// server listens before it loads (so that a balancer's health check gets NOT_SERVING rather than
// a refused connection, and a client a clear answer); until the gate opens every Recognition and
// Models call is refused with UNAVAILABLE, which clients retry (docs/scaling.md, "Health").
//
// Thread-safe.
#pragma once

#include <atomic>

#include <grpcpp/grpcpp.h>

namespace orbit::server {

class ServingGate {
 public:
  // Opens the gate for good: every later Admit() is OK.
  void Open() { open_.store(true, std::memory_order_release); }
  bool open() const { return open_.load(std::memory_order_acquire); }

  // OK once open; before, UNAVAILABLE saying the server is loading its models.
  grpc::Status Admit() const {
    if (open()) return grpc::Status::OK;
    return {grpc::StatusCode::UNAVAILABLE,
            "the server is starting: it is loading its model index; try again in a moment"};
  }

 private:
  std::atomic<bool> open_{false};
};

}  // namespace orbit::server
