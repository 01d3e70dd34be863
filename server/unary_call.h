// Runs a unary call's work on the worker pool after checking the caller's role and that the
// server has loaded its models (server/serving_gate.h), and finishes
// the call with the work's status (exceptions become statuses via StatusFromException). A call
// finds the pool's queue of calls full: RESOURCE_EXHAUSTED at once, naming the limit. A call
// whose caller has gone (cancelled, or past its deadline) before a worker takes it is dropped
// unrun; one the server's shutdown finds still queued is answered UNAVAILABLE
// (docs/design.md#work-queues). An administrative call's outcome, and any refused
// authentication, is recorded in the audit log. Keeps
// store reads and writes (fsync) off gRPC's threads. Refusals are counted in `metrics`: the
// caller's role and exceptions here, the statuses the work returns by the work itself
// (ServerMetrics::Refuse), since only it knows which rule refused.
#pragma once

#include <exception>
#include <string>
#include <string_view>
#include <utility>

#include <grpcpp/grpcpp.h>

#include "server/access_control.h"
#include "server/audit_log.h"
#include "server/calls_per_token.h"
#include "server/error_status.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/worker_pool.h"

namespace orbit::server {

// What a unary call is, for its checks, its queue and its audit.
struct UnaryCall {
  std::string_view name;  // "Models/DeleteObject": the name refusals are audited under
  Role role;              // the role its token needs
  WorkerPool& pool;
  // With role kAdmin, every outcome is recorded here (server/audit_log.h), naming `object`.
  AuditLog* audit = nullptr;
  std::string object = {};  // the object the call names; "" when none
  // Calls of this kind one token may have in progress (queued or running); nullptr: no limit.
  CallsPerToken* per_token = nullptr;
};

// `work` is called as grpc::Status work() on a pool thread; the response it fills must outlive
// the call (gRPC's response object does).
template <typename Work>
grpc::ServerUnaryReactor* RunUnaryCall(grpc::CallbackServerContext* context,
                                       const AccessControl& access, UnaryCall call,
                                       const ServingGate& gate, ServerMetrics& metrics, Work work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  std::string token;
  if (grpc::Status allowed = access.Authorize(*context, call.role, call.name, &token);
      !allowed.ok()) {
    reactor->Finish(metrics.Refuse(allowed, RefusalReason::kAccess));
    return reactor;
  }
  if (call.per_token != nullptr) {
    if (grpc::Status admitted = call.per_token->Acquire(token); !admitted.ok()) {
      reactor->Finish(metrics.Refuse(admitted, RefusalReason::kTokenCalls));
      return reactor;
    }
  }
  // Answers the call, recording an administrative call's outcome first, and gives its place
  // among its token's calls back.
  auto finish = [context, reactor, token, name = call.name, object = call.object,
                 audit = call.role == Role::kAdmin ? call.audit : nullptr,
                 per_token = call.per_token](const grpc::Status& status) {
    if (per_token != nullptr) per_token->Release(token);
    if (audit != nullptr) {
      const std::string peer = context->peer();
      audit->Record({.call = name,
                     .token = token,
                     .peer = peer,
                     .object = object,
                     .outcome = status.error_code(),
                     .message = status.error_message()});
    }
    reactor->Finish(status);
  };
  if (grpc::Status admitted = gate.Admit(); !admitted.ok()) {
    finish(metrics.Refuse(admitted, RefusalReason::kStarting));
    return reactor;
  }
  auto run = [context, finish, metrics = &metrics, work = std::move(work)]() mutable {
    if (context->IsCancelled()) {
      finish(metrics->Refuse(CallerGone(), RefusalReason::kCallerGone));
      return;
    }
    grpc::Status status;
    try {
      status = work();
    } catch (const std::exception& e) {
      status = metrics->Refuse(StatusFromException(e), RefusalReasonOf(e));
    }
    finish(status);
  };
  auto abandon = [finish, metrics = &metrics] {
    finish(metrics->Refuse(ShuttingDown(), RefusalReason::kShuttingDown));
  };
  if (!call.pool.TryPost({std::move(run), std::move(abandon)})) {
    finish(metrics.Refuse(QueueFull(call.pool.max_queued_calls()), RefusalReason::kQueueFull));
  }
  return reactor;
}

}  // namespace orbit::server
