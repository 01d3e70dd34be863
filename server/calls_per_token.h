// CallsPerToken: how many calls of one kind each token has in progress, held to a limit, so that
// one token cannot fill the workers' queue with its calls while other devices wait
// (docs/design.md#stream-limits). Calls without a token (no access control) are not counted.
//
// Thread-safe.
#pragma once

#include <string>
#include <unordered_map>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"

namespace orbit::server {

class CallsPerToken {
 public:
  // `limit` calls per token at once; 0: no limit. `flag` names it in refusals.
  CallsPerToken(int limit, std::string flag) : limit_(limit), flag_(std::move(flag)) {}

  // OK and counted, or RESOURCE_EXHAUSTED naming the limit when `token` already has `limit` calls
  // in progress. Every OK must be matched by one Release(token).
  grpc::Status Acquire(const std::string& token) ABSL_LOCKS_EXCLUDED(mutex_);
  void Release(const std::string& token) ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  const int limit_;
  const std::string flag_;
  Mutex mutex_;
  std::unordered_map<std::string, int> in_progress_ ABSL_GUARDED_BY(mutex_);
};

}  // namespace orbit::server
