#include "server/calls_per_token.h"

namespace orbit::server {

grpc::Status CallsPerToken::Acquire(const std::string& token) {
  if (token.empty() || limit_ <= 0) return grpc::Status::OK;
  MutexLock lock(&mutex_);
  int& count = in_progress_[token];
  if (count >= limit_) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "this token already has " + std::to_string(limit_) + " calls in progress (" + flag_ +
                "); wait for one to end"};
  }
  ++count;
  return grpc::Status::OK;
}

void CallsPerToken::Release(const std::string& token) {
  if (token.empty() || limit_ <= 0) return;
  MutexLock lock(&mutex_);
  const auto found = in_progress_.find(token);
  if (found != in_progress_.end() && --found->second <= 0) in_progress_.erase(found);
}

}  // namespace orbit::server
