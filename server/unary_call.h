// Runs a unary call's work on the worker pool after checking the caller's role, and finishes
// the call with the work's status (exceptions become statuses via StatusFromException). Keeps
// store reads and writes (fsync) off gRPC's threads.
#pragma once

#include <exception>
#include <utility>

#include <grpcpp/grpcpp.h>

#include "server/access_control.h"
#include "server/error_status.h"
#include "server/worker_pool.h"

namespace orbit::server {

// `work` is called as grpc::Status work() on a pool thread; the response it fills must outlive
// the call (gRPC's response object does).
template <typename Work>
grpc::ServerUnaryReactor* RunUnaryCall(grpc::CallbackServerContext* context,
                                       const AccessControl& access, Role role, WorkerPool& pool,
                                       Work work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  if (grpc::Status allowed = access.Authorize(*context, role); !allowed.ok()) {
    reactor->Finish(allowed);
    return reactor;
  }
  pool.Post([reactor, work = std::move(work)]() mutable {
    grpc::Status status;
    try {
      status = work();
    } catch (const std::exception& e) {
      status = StatusFromException(e);
    }
    reactor->Finish(status);
  });
  return reactor;
}

}  // namespace orbit::server
