#include "server/refusal_reason.h"

namespace orbit::server {

std::string_view RefusalReasonName(RefusalReason reason) {
  switch (reason) {
    case RefusalReason::kInvalidField: return "invalid_field";
    case RefusalReason::kAccess: return "access";
    case RefusalReason::kMaxSessions: return "max_sessions";
    case RefusalReason::kFrameRate: return "frame_rate";
    case RefusalReason::kSessionLimit: return "session_limit";
    case RefusalReason::kImageBudget: return "image_budget";
    case RefusalReason::kRequestSize: return "request_size";
    case RefusalReason::kIdleTimeout: return "idle_timeout";
    case RefusalReason::kShuttingDown: return "shutting_down";
    case RefusalReason::kUnknownObject: return "unknown_object";
    case RefusalReason::kDuplicateName: return "duplicate_name";
    case RefusalReason::kStore: return "store";
    case RefusalReason::kInternal: return "internal";
  }
  return "internal";
}

std::string_view StatusCodeName(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK: return "OK";
    case grpc::StatusCode::CANCELLED: return "CANCELLED";
    case grpc::StatusCode::UNKNOWN: return "UNKNOWN";
    case grpc::StatusCode::INVALID_ARGUMENT: return "INVALID_ARGUMENT";
    case grpc::StatusCode::DEADLINE_EXCEEDED: return "DEADLINE_EXCEEDED";
    case grpc::StatusCode::NOT_FOUND: return "NOT_FOUND";
    case grpc::StatusCode::ALREADY_EXISTS: return "ALREADY_EXISTS";
    case grpc::StatusCode::PERMISSION_DENIED: return "PERMISSION_DENIED";
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return "RESOURCE_EXHAUSTED";
    case grpc::StatusCode::FAILED_PRECONDITION: return "FAILED_PRECONDITION";
    case grpc::StatusCode::ABORTED: return "ABORTED";
    case grpc::StatusCode::OUT_OF_RANGE: return "OUT_OF_RANGE";
    case grpc::StatusCode::UNIMPLEMENTED: return "UNIMPLEMENTED";
    case grpc::StatusCode::INTERNAL: return "INTERNAL";
    case grpc::StatusCode::UNAVAILABLE: return "UNAVAILABLE";
    case grpc::StatusCode::DATA_LOSS: return "DATA_LOSS";
    case grpc::StatusCode::UNAUTHENTICATED: return "UNAUTHENTICATED";
    default: return "UNKNOWN";
  }
}

RefusalReason ReasonOfCheck(const grpc::Status& status, RefusalReason limit) {
  switch (status.error_code()) {
    case grpc::StatusCode::INVALID_ARGUMENT: return RefusalReason::kInvalidField;
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return limit;
    default: return RefusalReason::kInternal;
  }
}

}  // namespace orbit::server
