#include "server/recognition_service.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/frame_answer.h"
#include "server/request_reading.h"
#include "server/unary_call.h"

namespace orbit::server {
namespace {

// A stream refused before it starts (bad credentials).
class RefusedSession final : public grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate> {
 public:
  explicit RefusedSession(const grpc::Status& status) { Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace

grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate>* RecognitionService::Session(
    grpc::CallbackServerContext* context) {
  std::string token;
  if (grpc::Status allowed =
          access_.Authorize(*context, Role::kRecognize, "Recognition/Session", &token);
      !allowed.ok()) {
    return new RefusedSession(env_.metrics.Refuse(allowed, RefusalReason::kAccess));
  }
  if (grpc::Status admitted = env_.gate.Admit(); !admitted.ok()) {
    return new RefusedSession(env_.metrics.Refuse(admitted, RefusalReason::kStarting));
  }
  return new SessionReactor(env_, context, token);
}

grpc::ServerUnaryReactor* RecognitionService::Recognize(grpc::CallbackServerContext* context,
                                                        const v1::RecognizeRequest* request,
                                                        v1::RecognizeResponse* response) {
  // A batch with an image takes the image workers, like a session's image frame.
  const bool has_image = std::any_of(request->frames().begin(), request->frames().end(),
                                     [](const v1::Frame& frame) { return !frame.image().empty(); });
  WorkerPool& workers = has_image ? env_.bulk_pool : env_.pool;
  return RunUnaryCall(
      context, access_,
      {.name = "Recognition/Recognize",
       .role = Role::kRecognize,
       .pool = workers,
       .per_token = &recognize_calls_},
      env_.gate, env_.metrics, [this, context, request, response] {
        using Clock = std::chrono::steady_clock;
        ServerMetrics& metrics = env_.metrics;
        if (request->frames().empty()) {
          return metrics.Refuse(InvalidArgument("frames is empty"), RefusalReason::kInvalidField);
        }
        if (request->frames_size() > kMaxWindow) {
          return metrics.Refuse({grpc::StatusCode::RESOURCE_EXHAUSTED,
                                 "at most " + std::to_string(kMaxWindow) +
                                     " frames per Recognize call; stream longer sequences"},
                                RefusalReason::kRequestSize);
        }
        OpenedSession session;
        RefusalReason reason = RefusalReason::kInternal;
        if (grpc::Status opened = OpenSession(request->options(), env_, &session, &reason);
            !opened.ok()) {
          return metrics.Refuse(opened, reason);
        }
        // The batch is answered on the catalogue as it was when the call began.
        const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
        for (const v1::Frame& frame : request->frames()) {
          // A caller that has gone waits for nothing: the frames left are not worth a core.
          if (context->IsCancelled()) {
            return metrics.Refuse(CallerGone(), RefusalReason::kCallerGone);
          }
          if (grpc::Status answered = AnswerFrame(frame, Clock::now(), index, env_, session,
                                                  response->add_updates(), &reason);
              !answered.ok()) {
            return metrics.Refuse(answered, reason);
          }
        }
        return grpc::Status::OK;
      });
}

}  // namespace orbit::server
