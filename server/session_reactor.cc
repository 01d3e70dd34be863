#include "server/session_reactor.h"

#include <algorithm>
#include <string>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/request_reading.h"

namespace orbit::server {

SessionReactor::SessionReactor(const SessionEnvironment& environment,
                               grpc::CallbackServerContext* context)
    : env_(environment),
      context_(context),
      rate_limit_(environment.limits.max_frames_per_second, Clock::now()),
      read_started_(Clock::now()),
      previous_read_done_(read_started_),
      last_activity_(Clock::now().time_since_epoch().count()) {
  std::lock_guard lock(mutex_);
  const grpc::Status admitted = env_.registry.Add(this);
  if (!admitted.ok()) {
    FinishOnce(admitted);
    return;
  }
  registered_ = true;
  ReadNext();
}

void SessionReactor::OnReadDone(bool ok) {
  std::lock_guard lock(mutex_);
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
        FinishOnce({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"});
        return;
      }
      engine_->Reset();
      ReadNext();
      return;
    case v1::SessionRequest::kFrame:
      HandleFrame(now, previous_read_done);
      return;
    default:
      FinishOnce({grpc::StatusCode::INVALID_ARGUMENT,
                  "empty request: set one of open, frame or reset"});
  }
}

void SessionReactor::HandleOpen(const v1::SessionOptions& options) {
  if (engine_) {
    FinishOnce({grpc::StatusCode::INVALID_ARGUMENT, "`open` may be sent only once"});
    return;
  }
  SessionSettings settings;
  const grpc::Status resolved = ResolveSessionSettings(
      options, env_.defaults, env_.catalogue.variant(), env_.limits, &settings);
  if (!resolved.ok()) {
    FinishOnce(resolved);
    return;
  }
  engine_ = std::make_unique<SessionEngine>(settings);
  ReadNext();
}

void SessionReactor::HandleFrame(Clock::time_point received,
                                 Clock::time_point previous_read_done) {
  if (!engine_) {
    FinishOnce({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"});
    return;
  }
  if (!rate_limit_.Take(received, previous_read_done, read_started_)) {
    FinishOnce({grpc::StatusCode::RESOURCE_EXHAUSTED, rate_limit_.RefusalMessage()});
    return;
  }
  last_activity_ = received.time_since_epoch().count();
  busy_ = true;
  WorkerPool& workers = request_.frame().image().empty() ? env_.pool : env_.bulk_pool;
  workers.Post([this, frame = std::move(*request_.mutable_frame()), received]() mutable {
    Process(std::move(frame), received);
  });
}

void SessionReactor::Process(v1::Frame frame, Clock::time_point received) {
  // The engine is used only here and only while busy_, so never concurrently.
  QueryFrame query;
  grpc::Status status = ToQueryFrame(frame, env_.catalogue.variant(), env_.limits, &query);
  v1::SessionUpdate update;
  if (status.ok()) {
    try {
      const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
      update = ToSessionUpdate(engine_->Observe(index, query), *index);
    } catch (const std::exception& e) {
      status = StatusFromException(e);
    }
  }
  if (frame.has_timestamp_us()) update.set_timestamp_us(frame.timestamp_us());
  update.set_processing_time_us(
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - received).count());

  std::lock_guard lock(mutex_);
  if (!status.ok() || pending_close_) {
    busy_ = false;
    FinishOnce(status.ok() ? *pending_close_ : status);
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
    FinishOnce({grpc::StatusCode::CANCELLED, "the device stopped receiving updates"});
  } else if (pending_close_) {
    FinishOnce(*pending_close_);
  } else {
    ReadNext();
  }
}

void SessionReactor::Close(const grpc::Status& status) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  if (busy_) {
    if (!pending_close_) pending_close_ = status;
    // The device has not taken its update for a long while: it has stopped reading, and the
    // write would wait for it forever. Cancelling completes the write (not ok) and ends the
    // call, which frees the slot.
    if (write_started_ && Clock::now() - *write_started_ >= kStalledWrite) context_->TryCancel();
    return;
  }
  FinishOnce(status);  // a read is outstanding; it completes with ok = false
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

}  // namespace orbit::server
