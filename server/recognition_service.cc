#include "server/recognition_service.h"

#include <algorithm>
#include <chrono>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/request_reading.h"
#include "server/session_engine.h"
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
  if (grpc::Status allowed = access_.Authorize(*context, Role::kRecognize); !allowed.ok()) {
    return new RefusedSession(allowed);
  }
  return new SessionReactor(env_, context);
}

grpc::ServerUnaryReactor* RecognitionService::Recognize(grpc::CallbackServerContext* context,
                                                        const v1::RecognizeRequest* request,
                                                        v1::RecognizeResponse* response) {
  // A batch with an image takes the image workers, like a session's image frame.
  const bool has_image = std::any_of(request->frames().begin(), request->frames().end(),
                                     [](const v1::Frame& frame) { return !frame.image().empty(); });
  WorkerPool& workers = has_image ? env_.bulk_pool : env_.pool;
  return RunUnaryCall(context, access_, Role::kRecognize, workers, [this, request, response] {
    using Clock = std::chrono::steady_clock;
    if (request->frames().empty()) {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, "frames is empty");
    }
    if (request->frames_size() > kMaxWindow) {
      return grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                          "at most 64 frames per Recognize call; stream longer sequences");
    }
    SessionSettings settings;
    grpc::Status status = ResolveSessionSettings(request->options(), env_.defaults,
                                                 env_.catalogue.variant(), env_.limits, &settings);
    if (!status.ok()) return status;
    SessionEngine engine(settings);
    const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
    for (const v1::Frame& frame : request->frames()) {
      const Clock::time_point start = Clock::now();
      QueryFrame query;
      status = ToQueryFrame(frame, env_.catalogue.variant(), env_.limits, &query);
      if (!status.ok()) return status;
      v1::SessionUpdate* update = response->add_updates();
      *update = ToSessionUpdate(engine.Observe(index, query), *index);
      if (frame.has_timestamp_us()) update->set_timestamp_us(frame.timestamp_us());
      update->set_processing_time_us(
          std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count());
    }
    return grpc::Status::OK;
  });
}

}  // namespace orbit::server
