#include "server/frame_answer.h"

#include <exception>

#include "api/engines/conversion.h"
#include "core/descriptor/query_frame.h"
#include "server/error_status.h"
#include "server/request_reading.h"
#include "server/session_engine.h"
#include "server/session_settings.h"

namespace orbit::server {

grpc::Status OpenSession(const v1::SessionOptions& requested, const SessionEnvironment& env,
                         OpenedSession* out, RefusalReason* reason) {
  SessionSettings settings;
  const grpc::Status resolved = ResolveSessionSettings(
      requested, env.defaults, env.catalogue.variant(), env.limits, &settings);
  if (!resolved.ok()) {
    *reason = ReasonOfCheck(resolved, RefusalReason::kSessionLimit);
    return resolved;
  }
  out->engine = CreateSessionEngine(settings);
  out->metrics = env.metrics.ForEngine(settings.engine);
  return grpc::Status::OK;
}

grpc::Status AnswerFrame(const v1::Frame& frame, std::chrono::steady_clock::time_point received,
                         const std::shared_ptr<const ViewIndexSnapshot>& index,
                         const SessionEnvironment& env, OpenedSession& session,
                         v1::SessionUpdate* update, RefusalReason* reason) {
  using Clock = std::chrono::steady_clock;
  QueryFrame query;
  grpc::Status status = ToQueryFrame(frame, env.catalogue.variant(), env.limits, &query);
  if (!status.ok()) {
    *reason = ReasonOfCheck(status, RefusalReason::kImageBudget);
    return status;
  }
  try {
    session.engine->SetCalibration(env.calibrator.For(index));
    *update = ToSessionUpdate(session.engine->Observe(index, query), *index);
  } catch (const std::exception& e) {
    *reason = RefusalReasonOf(e);
    return StatusFromException(e);
  }
  if (frame.has_timestamp_us()) update->set_timestamp_us(frame.timestamp_us());
  const Clock::duration spent = Clock::now() - received;
  update->set_processing_time_us(
      std::chrono::duration_cast<std::chrono::microseconds>(spent).count());
  session.metrics.Record(frame.image().empty() ? FrameInput::kCedd : FrameInput::kImage, spent);
  return grpc::Status::OK;
}

}  // namespace orbit::server
