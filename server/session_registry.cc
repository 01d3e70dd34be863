#include "server/session_registry.h"

#include <algorithm>
#include <string>

#include "server/error_status.h"

namespace orbit::server {

grpc::Status SessionRegistry::Add(RegisteredSession* session, const std::string& token) {
  MutexLock lock(&mutex_);
  if (closed_) return ShuttingDown();
  if (static_cast<int>(sessions_.size()) >= limits_.max_open) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "this server already runs its maximum of " + std::to_string(limits_.max_open) + " " +
                limits_.noun + "s (" + limits_.flag + "); try again later"};
  }
  const bool capped = !token.empty() && limits_.max_open_per_token > 0;
  if (capped && per_token_[token] >= limits_.max_open_per_token) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "this token already holds its maximum of " +
                std::to_string(limits_.max_open_per_token) + " " + limits_.noun + "s (" +
                limits_.per_token_flag + "); close one or use a token of its own per device"};
  }
  sessions_.emplace(session, token);
  if (capped) ++per_token_[token];
  return grpc::Status::OK;
}

void SessionRegistry::Remove(RegisteredSession* session) {
  MutexLock lock(&mutex_);
  const auto found = sessions_.find(session);
  if (found == sessions_.end()) return;
  if (const auto count = per_token_.find(found->second); count != per_token_.end()) {
    if (--count->second == 0) per_token_.erase(count);
  }
  sessions_.erase(found);
}

void SessionRegistry::CloseIdle(std::chrono::steady_clock::time_point cutoff,
                                int idle_timeout_seconds) {
  MutexLock lock(&mutex_);
  for (const auto& [session, token] : sessions_) {
    if (session->last_activity() < cutoff) {
      session->Close({grpc::StatusCode::DEADLINE_EXCEEDED,
                      limits_.noun + " closed after " + std::to_string(idle_timeout_seconds) +
                          " s without " + limits_.activity});
    }
  }
}

void SessionRegistry::CloseTokens(const std::vector<std::string>& tokens,
                                  const grpc::Status& status) {
  MutexLock lock(&mutex_);
  for (const auto& [session, token] : sessions_) {
    if (!token.empty() && std::find(tokens.begin(), tokens.end(), token) != tokens.end()) {
      session->Close(status);
    }
  }
}

void SessionRegistry::CloseAll(const grpc::Status& status) {
  MutexLock lock(&mutex_);
  closed_ = true;
  for (const auto& [session, token] : sessions_) session->Close(status);
}

int SessionRegistry::size() const {
  MutexLock lock(&mutex_);
  return static_cast<int>(sessions_.size());
}

}  // namespace orbit::server
