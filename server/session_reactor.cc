#include "server/session_reactor.h"

#include <algorithm>
#include <string>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/request_reading.h"

namespace orbit::server {
namespace {

// The registry closes a session for its idle timeout (DEADLINE_EXCEEDED), its token's revocation
// (UNAUTHENTICATED) or the server's shutdown (UNAVAILABLE).
RefusalReason ReasonOfClose(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::DEADLINE_EXCEEDED: return RefusalReason::kIdleTimeout;
    case grpc::StatusCode::UNAUTHENTICATED: return RefusalReason::kAccess;  // token revoked
    default: return RefusalReason::kShuttingDown;
  }
}

}  // namespace

SessionReactor::SessionReactor(const SessionEnvironment& environment,
                               grpc::CallbackServerContext* context, const std::string& token)
    : env_(environment),
      context_(context),
      rate_limit_(environment.limits.max_frames_per_second, Clock::now()),
      read_started_(Clock::now()),
      previous_read_done_(read_started_),
      last_activity_(Clock::now().time_since_epoch().count()) {
  // Registered before mutex_ is taken: the registry calls Close, which takes mutex_, with its own
  // lock held, so taking the registry's lock under mutex_ would invert that order. Close may
  // therefore run before the lock below is taken; it finishes the stream, and no read starts.
  const grpc::Status admitted = env_.registry.Add(this, token);
  StreamOp op;
  {
    MutexLock lock(&mutex_);
    if (!admitted.ok()) {  // the session limit, or the server is shutting down
      op = Refuse(admitted, admitted.error_code() == grpc::StatusCode::UNAVAILABLE
                                ? RefusalReason::kShuttingDown
                                : RefusalReason::kMaxSessions);
    } else {
      registered_ = true;
      if (!finished_) op = ReadNext();
    }
  }
  Perform(op);
}

void SessionReactor::OnReadDone(bool ok) {
  StreamOp op;
  std::optional<FrameTask> task;
  {
    MutexLock lock(&mutex_);
    if (finished_) return;
    if (!ok) {  // the device closed its side (or the call broke): a clean end
      op = FinishOnce(grpc::Status::OK);
    } else if (pending_close_) {  // Close() came while this read was starting
      op = Refuse(*pending_close_, pending_reason_);
    } else {
      const Clock::time_point now = Clock::now();
      const Clock::time_point previous_read_done = previous_read_done_;
      previous_read_done_ = now;
      switch (request_.kind_case()) {
        case v1::SessionRequest::kOpen: op = HandleOpen(request_.open()); break;
        case v1::SessionRequest::kReset:
          if (!session_.engine) {
            op = Refuse({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"},
                        RefusalReason::kInvalidField);
            break;
          }
          session_.engine->Reset();
          op = ReadNext();
          break;
        case v1::SessionRequest::kFrame: op = HandleFrame(now, previous_read_done, &task); break;
        default:
          op = Refuse({grpc::StatusCode::INVALID_ARGUMENT,
                       "empty request: set one of open, frame or reset"},
                      RefusalReason::kInvalidField);
      }
    }
  }
  if (!task) {
    Perform(op);
  } else if (task->frame.image().empty()) {
    Process(std::move(*task));
  } else {
    env_.bulk_pool.Post(
        {.run = [this, task = std::move(*task)]() mutable { Process(std::move(task)); },
         .abandon = [this] { Abandon(); }});
  }
}

SessionReactor::StreamOp SessionReactor::HandleOpen(const v1::SessionOptions& options) {
  if (session_.engine) {
    return Refuse({grpc::StatusCode::INVALID_ARGUMENT, "`open` may be sent only once"},
                  RefusalReason::kInvalidField);
  }
  RefusalReason reason = RefusalReason::kInternal;
  if (grpc::Status opened = OpenSession(options, env_, &session_, &reason); !opened.ok()) {
    return Refuse(opened, reason);
  }
  return ReadNext();
}

SessionReactor::StreamOp SessionReactor::HandleFrame(Clock::time_point received,
                                                     Clock::time_point previous_read_done,
                                                     std::optional<FrameTask>* task) {
  if (!session_.engine) {
    return Refuse({grpc::StatusCode::INVALID_ARGUMENT, "the first request must be `open`"},
                  RefusalReason::kInvalidField);
  }
  if (!rate_limit_.Take(received, previous_read_done, read_started_)) {
    return Refuse({grpc::StatusCode::RESOURCE_EXHAUSTED, rate_limit_.RefusalMessage()},
                  RefusalReason::kFrameRate);
  }
  last_activity_ = received.time_since_epoch().count();
  busy_ = true;
  *task = FrameTask{std::move(*request_.mutable_frame()), received, &session_};
  return {};
}

void SessionReactor::Process(FrameTask task) {
  v1::SessionUpdate update;
  RefusalReason reason = RefusalReason::kInternal;
  const grpc::Status status = AnswerFrame(task.frame, task.received, env_.catalogue.Snapshot(),
                                          env_, *task.session, &update, &reason);

  StreamOp op;
  {
    MutexLock lock(&mutex_);
    if (!status.ok() || pending_close_) {
      busy_ = false;
      op = !status.ok() ? Refuse(status, reason) : Refuse(*pending_close_, pending_reason_);
    } else {
      update_ = std::move(update);
      write_started_ = Clock::now();
      op.kind = StreamOp::Kind::kWrite;
    }
  }
  Perform(op);
}

void SessionReactor::Abandon() {
  StreamOp op;
  {
    MutexLock lock(&mutex_);
    busy_ = false;
    op = pending_close_ ? Refuse(*pending_close_, pending_reason_)
                        : Refuse(ShuttingDown(), RefusalReason::kShuttingDown);
  }
  Perform(op);
}

void SessionReactor::OnWriteDone(bool ok) {
  StreamOp op;
  {
    MutexLock lock(&mutex_);
    busy_ = false;
    write_started_.reset();
    if (!ok) {
      // The device went away, or stopped reading and Close cancelled the call: then the refusal
      // is Close's (the idle timeout, the shutdown), though the device sees CANCELLED.
      if (pending_close_ && !finished_) {
        env_.metrics.CountRefusal(pending_close_->error_code(), pending_reason_);
      }
      op = FinishOnce({grpc::StatusCode::CANCELLED, "the device stopped receiving updates"});
    } else {
      op = ReadNext();  // or the pending close
    }
  }
  Perform(op);
}

void SessionReactor::Close(const grpc::Status& status) {
  StreamOp op;
  {
    MutexLock lock(&mutex_);
    if (finished_) return;
    if (busy_ || reads_starting_ > 0) {
      // Applied once the frame in hand is written, or once the read being started has.
      if (!pending_close_) {
        pending_close_ = status;
        pending_reason_ = ReasonOfClose(status);
      }
      // The device has not taken its update for a long while: it has stopped reading, and the
      // write would wait for it forever. Cancelling completes the write (not ok) and ends the
      // call, which frees the slot.
      if (write_started_ && Clock::now() - *write_started_ >= kStalledWrite) {
        op.kind = StreamOp::Kind::kCancel;
      }
    } else {
      // A read is outstanding; it completes with ok = false.
      op = Refuse(status, ReasonOfClose(status));
    }
  }
  // The registry's lock, held by the caller, keeps OnDone from deleting the reactor meanwhile.
  Perform(op);
}

void SessionReactor::OnDone() {
  bool registered = false;
  {
    MutexLock lock(&mutex_);
    registered = registered_;
  }
  if (registered) env_.registry.Remove(this);
  delete this;
}

std::chrono::steady_clock::time_point SessionReactor::last_activity() const {
  return Clock::time_point(Clock::duration(last_activity_.load()));
}

SessionReactor::StreamOp SessionReactor::ReadNext() {
  if (finished_) return {};
  if (pending_close_) return Refuse(*pending_close_, pending_reason_);
  read_started_ = Clock::now();
  ++reads_starting_;
  return {.kind = StreamOp::Kind::kRead, .status = {}};
}

SessionReactor::StreamOp SessionReactor::AfterReadStarted() {
  MutexLock lock(&mutex_);
  --reads_starting_;
  if (reads_starting_ > 0 || busy_ || !pending_close_) return {};
  return Refuse(*pending_close_, pending_reason_);
}

SessionReactor::StreamOp SessionReactor::FinishOnce(const grpc::Status& status) {
  if (finished_) return {};
  finished_ = true;
  return {.kind = StreamOp::Kind::kFinish, .status = status};
}

SessionReactor::StreamOp SessionReactor::Refuse(const grpc::Status& status, RefusalReason reason) {
  if (finished_) return {};
  env_.metrics.CountRefusal(status.error_code(), reason);
  return FinishOnce(status);
}

void SessionReactor::Perform(const StreamOp& op) {
  switch (op.kind) {
    case StreamOp::Kind::kNone: return;
    case StreamOp::Kind::kRead:
      StartRead(&request_);
      // The reactor is still there: kRead comes from a reaction or the constructor (StreamOp).
      Perform(AfterReadStarted());
      return;
    case StreamOp::Kind::kWrite: StartWrite(&update_); return;
    case StreamOp::Kind::kFinish: Finish(op.status); return;
    case StreamOp::Kind::kCancel: context_->TryCancel(); return;
  }
}

}  // namespace orbit::server
