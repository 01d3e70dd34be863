#include "server/frame_rate_limit.h"

#include <algorithm>
#include <sstream>

namespace orbit::server {

FrameRateLimit::FrameRateLimit(double frames_per_second, Clock::time_point now)
    : rate_(frames_per_second), allowance_(kBurstSeconds * frames_per_second), refilled_(now) {}

bool FrameRateLimit::Take(Clock::time_point now, Clock::time_point previous_read_done,
                          Clock::time_point read_started) {
  const auto seconds = [](Clock::duration d) {
    return std::max(0.0, std::chrono::duration<double>(d).count());
  };
  const double held = seconds(read_started - previous_read_done);
  const double capacity = rate_ * (kBurstSeconds + held);
  const double refilled = allowance_ + seconds(now - refilled_) * rate_;
  // Refill up to the capacity, but never take away what an earlier stall's credit left.
  allowance_ = std::max(allowance_, std::min(capacity, refilled));
  refilled_ = now;
  if (allowance_ < 1) return false;
  allowance_ -= 1;
  return true;
}

std::string FrameRateLimit::RefusalMessage() const {
  std::ostringstream message;
  message << "more than " << rate_ << " frames per second (the server's --max-fps)";
  return message.str();
}

}  // namespace orbit::server
