#include "client/capture_session.h"

#include <chrono>
#include <cmath>
#include <thread>

namespace orbit {

CaptureStreamResult StreamCapture(RecognitionSession& session, CaptureReader& capture,
                                  const CaptureStreamOptions& options) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point next_allowed = start;
  CaptureStreamResult result;
  VideoFrame frame;
  while (capture.Next(frame)) {
    ++result.frames_read;
    if (frame.lost) {
      ++result.frames_lost;
    } else {
      Clock::time_point due = next_allowed;
      if (options.real_time) {
        due = std::max(due,
                       start + std::chrono::microseconds(std::llround(frame.timestamp_ms * 1000)));
      }
      std::this_thread::sleep_until(due);
      next_allowed = Clock::now() + session.min_frame_interval();
      session.Push(frame.image, frame.orientation.azimuth_deg, frame.region,
                   std::llround(frame.timestamp_ms * 1000), frame.quality);
      ++result.frames_sent;
    }
    if (options.progress) options.progress(result.frames_read, capture.frame_count());
  }
  return result;
}

}  // namespace orbit
