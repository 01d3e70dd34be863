// Why the server refused a request: the fixed vocabulary of the `reason` label of
// orbit_refusals_total (docs/service.md, "Metrics"), beside the status code the client gets.
// The code says what kind of answer the client got; the reason says which of the server's rules
// gave it, so an operator can tell a device over its frame rate from one sending bad descriptors.
#pragma once

#include <grpcpp/grpcpp.h>

#include <array>
#include <string_view>
#include <utility>

namespace orbit::server {

enum class RefusalReason {
  kInvalidField,    // invalid_field: a request the API does not allow: a field's value
                    // (descriptor, azimuth, image data, option, name, page token, ...) or a
                    // stream's messages out of order (a frame before `open`, `open` twice, an
                    // empty request, an enrollment without views); the message says which
  kAccess,          // access: no token, an unknown one, or one without the needed role
  kMaxSessions,     // max_sessions: --max-sessions streams already open, or
                    // --max-sessions-per-token of the caller's token
  kMaxEnrollments,  // max_enrollments: --max-enrollments Enroll streams already open
  kTokenCalls,      // token_calls: --max-recognize-calls-per-token of the caller's token's
                    // Recognize calls already in progress
  kFrameRate,       // frame_rate: a session over --max-fps
  kSessionLimit,    // session_limit: window above --max-window, window x HMM states above
                    // --max-hmm-cells
  kImageBudget,     // image_budget: an image above --max-image-pixels, or a JPEG of too many scans
  kRequestSize,     // request_size: too many views or bytes in one enrollment, more than 64
                    // frames in one Recognize call
  kIdleTimeout,     // idle_timeout: a session without a frame for --idle-timeout
  kShuttingDown,    // shutting_down: the server is stopping
  kQueueFull,       // queue_full: --max-queued-calls calls already wait for a worker
  kCallerGone,      // caller_gone: a call cancelled, or past its deadline, before its work was
                    // done: dropped, the rest of its work not done
  kStarting,        // starting: the server is still loading its model index (server/serving_gate.h)
  kUnknownObject,   // unknown_object: no object with that id or name
  kDuplicateName,   // duplicate_name: an object of that name is already enrolled
  kStore,           // store: the model store failed (full, busy, I/O, corrupt)
  kInternal,        // internal: anything else that went wrong on the server
};
inline constexpr int kRefusalReasonCount = static_cast<int>(RefusalReason::kInternal) + 1;

// The label value, e.g. "frame_rate".
std::string_view RefusalReasonName(RefusalReason reason);

// Every (code, reason) pair the server answers with, so that each series exists, at 0, from
// the start (a counter that appears only at its first increment hides that first increment
// from rate() and increase()).
inline constexpr std::array<std::pair<grpc::StatusCode, RefusalReason>, 21> kRefusalKinds = {{
    {grpc::StatusCode::INVALID_ARGUMENT, RefusalReason::kInvalidField},
    {grpc::StatusCode::UNAUTHENTICATED, RefusalReason::kAccess},
    {grpc::StatusCode::PERMISSION_DENIED, RefusalReason::kAccess},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kMaxSessions},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kMaxEnrollments},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kTokenCalls},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kFrameRate},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kSessionLimit},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kImageBudget},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kRequestSize},
    {grpc::StatusCode::DEADLINE_EXCEEDED, RefusalReason::kIdleTimeout},
    {grpc::StatusCode::UNAVAILABLE, RefusalReason::kShuttingDown},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kQueueFull},
    {grpc::StatusCode::CANCELLED, RefusalReason::kCallerGone},
    {grpc::StatusCode::UNAVAILABLE, RefusalReason::kStarting},
    {grpc::StatusCode::NOT_FOUND, RefusalReason::kUnknownObject},
    {grpc::StatusCode::ALREADY_EXISTS, RefusalReason::kDuplicateName},
    {grpc::StatusCode::RESOURCE_EXHAUSTED, RefusalReason::kStore},
    {grpc::StatusCode::UNAVAILABLE, RefusalReason::kStore},
    {grpc::StatusCode::INTERNAL, RefusalReason::kStore},
    {grpc::StatusCode::INTERNAL, RefusalReason::kInternal},
}};

// The reason for a refusal by a check that answers INVALID_ARGUMENT for a bad value and
// RESOURCE_EXHAUSTED for one of the server's limits (ResolveSessionSettings: kSessionLimit;
// ToQueryFrame, ToModelView: kImageBudget): invalid_field for INVALID_ARGUMENT, `limit` for
// RESOURCE_EXHAUSTED, internal for any other code.
RefusalReason ReasonOfCheck(const grpc::Status& status, RefusalReason limit);

}  // namespace orbit::server
