// SessionRegistry: the open streams of one kind (recognition sessions, enrollments), for the
// limits on their number, in all and per token, the idle timeout and a clean end at shutdown
// (docs/design.md#stream-limits).
//
// Thread-safe. A session registers when it opens and leaves in its OnDone; Close() is called
// with the registry's lock held, which is safe because gRPC never runs OnDone inside Finish. A
// session's own lock is therefore taken after the registry's, never before (a session declares
// that with ABSL_ACQUIRED_AFTER(registry.mutex())).
#pragma once

#include <chrono>
#include <string>
#include <unordered_map>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"

namespace orbit::server {

// What the registry needs of a session.
class RegisteredSession {
 public:
  virtual ~RegisteredSession() = default;
  // Ends the stream with `status` as soon as no frame is being processed or written.
  virtual void Close(const grpc::Status& status) = 0;
  // When the session last received a frame (or opened).
  virtual std::chrono::steady_clock::time_point last_activity() const = 0;
};

// The streams a registry holds, as its refusals name them.
struct StreamLimits {
  int max_open = 256;
  int max_open_per_token = 0;    // streams one token may hold at once; 0: no such limit
  std::string noun = "session";  // "session closed after ..."
  std::string flag = "--max-sessions";
  std::string per_token_flag = "--max-sessions-per-token";
  std::string activity = "a frame";  // "... s without a frame"
};

class SessionRegistry {
 public:
  explicit SessionRegistry(StreamLimits limits) : limits_(std::move(limits)) {}

  // Admits `session`, opened with the token named `token` ("" without access control), unless
  // max_open are open, or max_open_per_token of that token's (RESOURCE_EXHAUSTED naming the
  // limit and its flag), or the server is shutting down (UNAVAILABLE).
  grpc::Status Add(RegisteredSession* session, const std::string& token = "")
      ABSL_LOCKS_EXCLUDED(mutex_);
  void Remove(RegisteredSession* session) ABSL_LOCKS_EXCLUDED(mutex_);

  // Closes, with DEADLINE_EXCEEDED, every stream idle since before `cutoff`.
  void CloseIdle(std::chrono::steady_clock::time_point cutoff, int idle_timeout_seconds)
      ABSL_LOCKS_EXCLUDED(mutex_);

  // Closes every stream opened with one of `tokens` (names) with `status`.
  void CloseTokens(const std::vector<std::string>& tokens, const grpc::Status& status)
      ABSL_LOCKS_EXCLUDED(mutex_);

  // Refuses new sessions from now on and closes every open one with `status`.
  void CloseAll(const grpc::Status& status) ABSL_LOCKS_EXCLUDED(mutex_);

  int size() const ABSL_LOCKS_EXCLUDED(mutex_);
  const StreamLimits& limits() const { return limits_; }

  // The lock held while a session's Close() runs: named by the sessions' lock-order
  // annotations. Not to be taken outside the registry.
  Mutex& mutex() const ABSL_LOCK_RETURNED(mutex_) { return mutex_; }

 private:
  const StreamLimits limits_;
  mutable Mutex mutex_;
  // Each open stream, with the token it was opened with.
  std::unordered_map<RegisteredSession*, std::string> sessions_ ABSL_GUARDED_BY(mutex_);
  std::unordered_map<std::string, int> per_token_ ABSL_GUARDED_BY(mutex_);
  bool closed_ ABSL_GUARDED_BY(mutex_) = false;
};

}  // namespace orbit::server
