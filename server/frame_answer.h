// The work of a recognition session, written once for a Session stream (server/session_reactor.h)
// and a Recognize call (server/recognition_service.h): opening it (its options resolved, its
// engine built) and answering one frame.
#pragma once

#include <chrono>
#include <memory>

#include <grpcpp/grpcpp.h>

#include "core/engines/recognition_engine.h"
#include "core/index/view_index.h"
#include "orbit/v1/recognition.pb.h"
#include "server/refusal_reason.h"
#include "server/server_metrics.h"
#include "server/session_environment.h"

namespace orbit::server {

// A session's engine and the metrics its frames are counted in.
struct OpenedSession {
  std::unique_ptr<RecognitionEngine> engine;
  FrameMetrics metrics;
};

// The session `requested` asks for, over the server's defaults and within its limits
// (ResolveSessionSettings). On refusal, returns the status and sets `reason`, the refusal's
// counter, and leaves `out` unchanged.
grpc::Status OpenSession(const v1::SessionOptions& requested, const SessionEnvironment& env,
                         OpenedSession* out, RefusalReason* reason);

// One frame of `session`: read (ToQueryFrame: its checks, an image described here as the client
// library describes it), answered on `index` with that snapshot's calibration, converted, stamped
// with the frame's timestamp and the time spent since `received`, and counted in the session's
// metrics. On refusal (a bad frame, an image over budget), returns the status and sets `reason`;
// the session's window is then unchanged.
grpc::Status AnswerFrame(const v1::Frame& frame, std::chrono::steady_clock::time_point received,
                         const std::shared_ptr<const ViewIndexSnapshot>& index,
                         const SessionEnvironment& env, OpenedSession& session,
                         v1::SessionUpdate* update, RefusalReason* reason);

}  // namespace orbit::server
