#include "server/refusal_reason.h"

namespace orbit::server {

std::string_view RefusalReasonName(RefusalReason reason) {
  switch (reason) {
    case RefusalReason::kInvalidField: return "invalid_field";
    case RefusalReason::kAccess: return "access";
    case RefusalReason::kMaxSessions: return "max_sessions";
    case RefusalReason::kMaxEnrollments: return "max_enrollments";
    case RefusalReason::kTokenCalls: return "token_calls";
    case RefusalReason::kFrameRate: return "frame_rate";
    case RefusalReason::kSessionLimit: return "session_limit";
    case RefusalReason::kImageBudget: return "image_budget";
    case RefusalReason::kRequestSize: return "request_size";
    case RefusalReason::kIdleTimeout: return "idle_timeout";
    case RefusalReason::kShuttingDown: return "shutting_down";
    case RefusalReason::kQueueFull: return "queue_full";
    case RefusalReason::kCallerGone: return "caller_gone";
    case RefusalReason::kStarting: return "starting";
    case RefusalReason::kUnknownObject: return "unknown_object";
    case RefusalReason::kDuplicateName: return "duplicate_name";
    case RefusalReason::kStore: return "store";
    case RefusalReason::kInternal: return "internal";
  }
  return "internal";
}

RefusalReason ReasonOfCheck(const grpc::Status& status, RefusalReason limit) {
  switch (status.error_code()) {
    case grpc::StatusCode::INVALID_ARGUMENT: return RefusalReason::kInvalidField;
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return limit;
    default: return RefusalReason::kInternal;
  }
}

}  // namespace orbit::server
