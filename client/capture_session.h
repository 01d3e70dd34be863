// StreamCapture: a recognition session fed by a capture: every frame of the
// CaptureReader whose object is tracked is pushed with its azimuth, its region, its time and
// its quality, at the video's own rate or as fast as the server allows.
//
// Frames whose tracking is lost are not sent (their box would describe the background); the
// result counts them. Updates arrive as the session delivers them (RecognitionOptions::on_update or
// NextUpdate); this function does not close the session.
// Errors: as CaptureReader::Next and RecognitionSession::Push (RpcError once the session ended).
#pragma once

#include <functional>

#include "client/capture_reader.h"
#include "client/recognition_session.h"

namespace orbit {

struct CaptureStreamOptions {
  // true: one frame per 1/fps of the video, as the device filmed it; false: as fast as the
  // server's frame-rate limit allows (RecognitionSession::min_frame_interval).
  bool real_time = true;
  // Called after each frame read with the frames read so far and the capture's frame count
  // (0 when unknown).
  std::function<void(long read, long total)> progress;
};

struct CaptureStreamResult {
  long frames_read = 0;
  long frames_sent = 0;
  long frames_lost = 0;  // not sent: tracking lost
};

CaptureStreamResult StreamCapture(RecognitionSession& session, CaptureReader& capture,
                                  const CaptureStreamOptions& options = {});

}  // namespace orbit
