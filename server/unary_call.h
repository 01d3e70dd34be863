// Runs a unary call's work on the worker pool after checking the caller's role and that the
// server has loaded its models (server/serving_gate.h), and finishes
// the call with the work's status (exceptions become statuses via StatusFromException). A call
// finds the pool's queue of calls full: RESOURCE_EXHAUSTED at once, naming the limit. A call
// whose caller has gone (cancelled, or past its deadline) before a worker takes it is dropped
// unrun; one the server's shutdown finds still queued is answered UNAVAILABLE
// (docs/design.md#work-queues). Keeps
// store reads and writes (fsync) off gRPC's threads. Refusals are counted in `metrics`: the
// caller's role and exceptions here, the statuses the work returns by the work itself
// (ServerMetrics::Refuse), since only it knows which rule refused.
#pragma once

#include <exception>
#include <utility>

#include <grpcpp/grpcpp.h>

#include "server/access_control.h"
#include "server/error_status.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/worker_pool.h"

namespace orbit::server {

// `work` is called as grpc::Status work() on a pool thread; the response it fills must outlive
// the call (gRPC's response object does).
template <typename Work>
grpc::ServerUnaryReactor* RunUnaryCall(grpc::CallbackServerContext* context,
                                       const AccessControl& access, Role role,
                                       const ServingGate& gate, WorkerPool& pool,
                                       ServerMetrics& metrics, Work work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  if (grpc::Status allowed = access.Authorize(*context, role); !allowed.ok()) {
    reactor->Finish(metrics.Refuse(allowed, RefusalReason::kAccess));
    return reactor;
  }
  if (grpc::Status admitted = gate.Admit(); !admitted.ok()) {
    reactor->Finish(metrics.Refuse(admitted, RefusalReason::kStarting));
    return reactor;
  }
  auto run = [context, reactor, metrics = &metrics, work = std::move(work)]() mutable {
    if (context->IsCancelled()) {
      reactor->Finish(metrics->Refuse(CallerGone(), RefusalReason::kCallerGone));
      return;
    }
    grpc::Status status;
    try {
      status = work();
    } catch (const std::exception& e) {
      status = metrics->Refuse(StatusFromException(e), RefusalReasonOf(e));
    }
    reactor->Finish(status);
  };
  auto abandon = [reactor, metrics = &metrics] {
    reactor->Finish(metrics->Refuse(ShuttingDown(), RefusalReason::kShuttingDown));
  };
  if (!pool.TryPost({std::move(run), std::move(abandon)})) {
    reactor->Finish(metrics.Refuse(QueueFull(pool.max_queued_calls()), RefusalReason::kQueueFull));
  }
  return reactor;
}

}  // namespace orbit::server
