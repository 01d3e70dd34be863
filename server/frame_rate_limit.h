// FrameRateLimit: a session's limit on frames per second (ServerLimits::max_frames_per_second),
// measured on what the device sent, not on what a stall of the server queued.
//
// A token bucket holding up to kBurstSeconds of frames, refilled at the rate. The server reads
// a session's frames one at a time; while it holds the stream (processing a frame, writing its
// update, or stalled), the device's frames wait in the transport and then arrive together. So
// each read is told when the server started it: the time the server held the stream before it
// lets the bucket hold that much more (the frames the device sent meanwhile at the allowed
// rate), and a burst that merely catches up on a stall is admitted, while a device that really
// sends faster than the rate is still refused.
//
// Not thread-safe: one per session, used under the session's lock.
#pragma once

#include <chrono>
#include <string>

namespace orbit::server {

class FrameRateLimit {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double kBurstSeconds = 2;

  // REQUIRES: frames_per_second > 0. The bucket starts full.
  FrameRateLimit(double frames_per_second, Clock::time_point now);

  // Takes one frame read at `now` from a read the server started at `read_started`, after
  // having finished the previous read at `previous_read_done` (the server held the stream in
  // between). False when the device is over the rate.
  bool Take(Clock::time_point now, Clock::time_point previous_read_done,
            Clock::time_point read_started);

  // "more than R frames per second", R as an operator wrote it (60, not 60.000000).
  std::string RefusalMessage() const;

 private:
  double rate_;
  double allowance_;
  Clock::time_point refilled_;
};

}  // namespace orbit::server
