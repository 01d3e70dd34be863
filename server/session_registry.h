// SessionRegistry: the open recognition sessions, for the limit on their number, the idle
// timeout and a clean end at shutdown.
//
// Thread-safe. A session registers when it opens and leaves in its OnDone; Close() is called
// with the registry's lock held, which is safe because gRPC never runs OnDone inside Finish. A
// session's own lock is therefore taken after the registry's, never before (a session declares
// that with ABSL_ACQUIRED_AFTER(registry.mutex())).
#pragma once

#include <chrono>
#include <unordered_set>

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

class SessionRegistry {
 public:
  explicit SessionRegistry(int max_sessions) : max_sessions_(max_sessions) {}

  // Admits `session` unless max_sessions are open (RESOURCE_EXHAUSTED) or the server is
  // shutting down (UNAVAILABLE).
  grpc::Status Add(RegisteredSession* session) ABSL_LOCKS_EXCLUDED(mutex_);
  void Remove(RegisteredSession* session) ABSL_LOCKS_EXCLUDED(mutex_);

  // Closes, with DEADLINE_EXCEEDED, every session idle since before `cutoff`.
  void CloseIdle(std::chrono::steady_clock::time_point cutoff, int idle_timeout_seconds)
      ABSL_LOCKS_EXCLUDED(mutex_);

  // Refuses new sessions from now on and closes every open one with `status`.
  void CloseAll(const grpc::Status& status) ABSL_LOCKS_EXCLUDED(mutex_);

  int size() const ABSL_LOCKS_EXCLUDED(mutex_);

  // The lock held while a session's Close() runs: named by the sessions' lock-order
  // annotations. Not to be taken outside the registry.
  Mutex& mutex() const ABSL_LOCK_RETURNED(mutex_) { return mutex_; }

 private:
  const int max_sessions_;
  mutable Mutex mutex_;
  std::unordered_set<RegisteredSession*> sessions_ ABSL_GUARDED_BY(mutex_);
  bool closed_ ABSL_GUARDED_BY(mutex_) = false;
};

}  // namespace orbit::server
