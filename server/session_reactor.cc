#include "server/session_reactor.h"

#include <algorithm>
#include <string>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/request_reading.h"

namespace orbit::server {
namespace {

// The registry closes a session for its idle timeout (DEADLINE_EXCEEDED) or for the server's
// shutdown (UNAVAILABLE).
RefusalReason ReasonOfClose(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED ? RefusalReason::kIdleTimeout
                                                                    : RefusalReason::kShuttingDown;
}

}  // namespace

SessionReactor::SessionReactor(const SessionEnvironment& environment,
                               grpc::CallbackServerContext* context)
    : env_(environment),
      context_(context),
      rate_limit_(environment.limits.max_frames_per_second, Clock::now()),
      read_started_(Clock::now()),
      previous_read_done_(read_started_),
      last_activity_(Clock::now().time_since_epoch().count()) {
  // Registered before mutex_ is taken: the registry calls Close, which takes mutex_, with its own
  // lock held, so taking the registry's lock under mutex_ would invert that order. Close may
  // therefore run before the lock below is taken; it finishes the stream, and no read starts.
  const grpc::Status admitted = env_.registry.Add(this);
  std::lock_guard lock(mutex_);
  if (!admitted.ok()) {  // the session limit, or the server is shutting down
    Refuse(admitted, admitted.error_code() == grpc::StatusCode::UNAVAILABLE
                         ? RefusalReason::kShuttingDown
                         : RefusalReason::kMaxSessions);
    return;
  }
  registered_ = true;
  if (!finished_) ReadNext();
}

void SessionReactor::OnReadDone(bool ok) {
  std::unique_lock lock(mutex_);
  if (finished_) return;
  if (!ok) {  // the device closed its side (or the call broke): a clean end
    FinishOnce(grpc::Status::OK);
    return;
  }
  const Clock::time_point now = Clock::now();
  const Clock::time_point previous_read_done = previous_read_done_;
  previous_read_done_ = now;
  switch (request_.kind_case()) {
    case v1::SessionRequest::kOpen:
      HandleOpen(request_.open());
      return;
    case v1::SessionRequest::kReset:
      if (!engine_) {
        Refuse({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"},
               RefusalReason::kInvalidField);
        return;
      }
      engine_->Reset();
      ReadNext();
      return;
    case v1::SessionRequest::kFrame:
      if (HandleFrame(now, previous_read_done)) {
        lock.unlock();
        Process(std::move(*request_.mutable_frame()), now);
      }
      return;
    default:
      Refuse({grpc::StatusCode::INVALID_ARGUMENT, "empty request: set one of open, frame or reset"},
             RefusalReason::kInvalidField);
  }
}

void SessionReactor::HandleOpen(const v1::SessionOptions& options) {
  if (engine_) {
    Refuse({grpc::StatusCode::INVALID_ARGUMENT, "`open` may be sent only once"},
           RefusalReason::kInvalidField);
    return;
  }
  SessionSettings settings;
  const grpc::Status resolved = ResolveSessionSettings(
      options, env_.defaults, env_.catalogue.variant(), env_.limits, &settings);
  if (!resolved.ok()) {
    Refuse(resolved, ReasonOfCheck(resolved, RefusalReason::kSessionLimit));
    return;
  }
  engine_ = CreateSessionEngine(settings);
  frame_metrics_ = env_.metrics.ForEngine(settings.engine);
  ReadNext();
}

bool SessionReactor::HandleFrame(Clock::time_point received,
                                 Clock::time_point previous_read_done) {
  if (!engine_) {
    Refuse({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"},
           RefusalReason::kInvalidField);
    return false;
  }
  if (!rate_limit_.Take(received, previous_read_done, read_started_)) {
    Refuse({grpc::StatusCode::RESOURCE_EXHAUSTED, rate_limit_.RefusalMessage()},
           RefusalReason::kFrameRate);
    return false;
  }
  last_activity_ = received.time_since_epoch().count();
  busy_ = true;
  if (request_.frame().image().empty()) return true;  // processed by the caller, unlocked
  env_.bulk_pool.Post([this, frame = std::move(*request_.mutable_frame()), received]() mutable {
    Process(std::move(frame), received);
  });
  return false;
}

void SessionReactor::Process(v1::Frame frame, Clock::time_point received) {
  // The engine is used only here and only while busy_, so never concurrently.
  QueryFrame query;
  grpc::Status status = ToQueryFrame(frame, env_.catalogue.variant(), env_.limits, &query);
  RefusalReason reason = ReasonOfCheck(status, RefusalReason::kImageBudget);
  v1::SessionUpdate update;
  if (status.ok()) {
    try {
      const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
      engine_->SetCalibration(env_.calibrator.For(index));
      update = ToSessionUpdate(engine_->Observe(index, query), *index);
    } catch (const std::exception& e) {
      status = StatusFromException(e);
      reason = RefusalReasonOf(e);
    }
  }
  if (frame.has_timestamp_us()) update.set_timestamp_us(frame.timestamp_us());
  const Clock::duration spent = Clock::now() - received;
  update.set_processing_time_us(
      std::chrono::duration_cast<std::chrono::microseconds>(spent).count());
  if (status.ok()) {
    frame_metrics_.Record(frame.image().empty() ? FrameInput::kCedd : FrameInput::kImage, spent);
  }

  std::lock_guard lock(mutex_);
  if (!status.ok() || pending_close_) {
    busy_ = false;
    if (!status.ok()) {
      Refuse(status, reason);
    } else {
      Refuse(*pending_close_, pending_reason_);
    }
    return;
  }
  update_ = std::move(update);
  write_started_ = Clock::now();
  StartWrite(&update_);
}

void SessionReactor::OnWriteDone(bool ok) {
  std::lock_guard lock(mutex_);
  busy_ = false;
  write_started_.reset();
  if (!ok) {
    // The device went away, or stopped reading and Close cancelled the call: then the refusal
    // is Close's (the idle timeout, the shutdown), though the device sees CANCELLED.
    if (pending_close_ && !finished_) {
      env_.metrics.CountRefusal(pending_close_->error_code(), pending_reason_);
    }
    FinishOnce({grpc::StatusCode::CANCELLED, "the device stopped receiving updates"});
  } else if (pending_close_) {
    Refuse(*pending_close_, pending_reason_);
  } else {
    ReadNext();
  }
}

void SessionReactor::Close(const grpc::Status& status) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  if (busy_) {
    if (!pending_close_) {
      pending_close_ = status;
      pending_reason_ = ReasonOfClose(status);
    }
    // The device has not taken its update for a long while: it has stopped reading, and the
    // write would wait for it forever. Cancelling completes the write (not ok) and ends the
    // call, which frees the slot.
    if (write_started_ && Clock::now() - *write_started_ >= kStalledWrite) context_->TryCancel();
    return;
  }
  Refuse(status, ReasonOfClose(status));  // a read is outstanding; it completes with ok = false
}

void SessionReactor::OnDone() {
  if (registered_) env_.registry.Remove(this);
  delete this;
}

std::chrono::steady_clock::time_point SessionReactor::last_activity() const {
  return Clock::time_point(Clock::duration(last_activity_.load()));
}

void SessionReactor::ReadNext() {
  read_started_ = Clock::now();
  StartRead(&request_);
}

void SessionReactor::FinishOnce(const grpc::Status& status) {
  if (finished_) return;
  finished_ = true;
  Finish(status);
}

void SessionReactor::Refuse(const grpc::Status& status, RefusalReason reason) {
  if (finished_) return;
  env_.metrics.CountRefusal(status.error_code(), reason);
  FinishOnce(status);
}

}  // namespace orbit::server
