#include "server/session_registry.h"

#include <string>

namespace orbit::server {

grpc::Status SessionRegistry::Add(RegisteredSession* session) {
  MutexLock lock(&mutex_);
  if (closed_) return {grpc::StatusCode::UNAVAILABLE, "the server is shutting down"};
  if (static_cast<int>(sessions_.size()) >= max_sessions_) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "this server already runs its maximum of " +
                                                      std::to_string(max_sessions_) +
                                                      " sessions; try again later"};
  }
  sessions_.insert(session);
  return grpc::Status::OK;
}

void SessionRegistry::Remove(RegisteredSession* session) {
  MutexLock lock(&mutex_);
  sessions_.erase(session);
}

void SessionRegistry::CloseIdle(std::chrono::steady_clock::time_point cutoff,
                                int idle_timeout_seconds) {
  MutexLock lock(&mutex_);
  for (RegisteredSession* session : sessions_) {
    if (session->last_activity() < cutoff) {
      session->Close(
          {grpc::StatusCode::DEADLINE_EXCEEDED,
           "session closed after " + std::to_string(idle_timeout_seconds) + " s without a frame"});
    }
  }
}

void SessionRegistry::CloseAll(const grpc::Status& status) {
  MutexLock lock(&mutex_);
  closed_ = true;
  for (RegisteredSession* session : sessions_) session->Close(status);
}

int SessionRegistry::size() const {
  MutexLock lock(&mutex_);
  return static_cast<int>(sessions_.size());
}

}  // namespace orbit::server
