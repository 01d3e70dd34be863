#include "cli/load_session.h"

#include <algorithm>
#include <utility>

#include "api/status_code_name.h"
#include "client/rpc_error.h"

namespace orbit {

LoadSession::LoadSession(int number, const std::vector<TurntableView>& turntable, bool image_frames,
                         bool closed_loop, const LoadShared& shared)
    : turntable_(turntable),
      first_view_(static_cast<std::size_t>(number) * 7 % turntable.size()),
      compass_offset_(number * 37 % 360),
      image_frames_(image_frames),
      closed_loop_(closed_loop),
      shared_(shared) {}

void LoadSession::Start(v1::Recognition::Stub& stub, const Connection& connection,
                        const v1::SessionOptions& open) {
  connection.PrepareStreamingCall(context_);
  stub.async()->Session(&context_, this);
  {
    MutexLock lock(&mutex_);
    *queued_.emplace_back().mutable_open() = open;
  }
  StartRead(&update_);
  StartCall();
  WriteNext();
}

bool LoadSession::SendFrame(std::int64_t k, Clock::time_point due) {
  const std::size_t position = first_view_ + static_cast<std::size_t>(k);
  const TurntableView& view = turntable_[position % turntable_.size()];
  v1::SessionRequest request;
  v1::Frame* frame = request.mutable_frame();
  if (image_frames_) {
    frame->set_image(view.encoded);
  } else {
    frame->set_cedd(view.cedd);
    frame->set_appearance(view.appearance);
  }
  // The turntable keeps turning: each lap adds 360 degrees.
  frame->set_azimuth_deg(view.azimuth + 360.0 * static_cast<double>(position / turntable_.size()) +
                         compass_offset_);
  frame->set_timestamp_us(
      std::chrono::duration_cast<std::chrono::microseconds>(due - shared_.clock.start).count());
  {
    MutexLock lock(&mutex_);
    if (done_ || closing_) return false;
    queued_.push_back(std::move(request));
    ++sent_;
    sent_while_enrolling_.push_back(shared_.enrolling.load() > 0);
  }
  WriteNext();
  return true;
}

void LoadSession::CloseWrites() {
  {
    MutexLock lock(&mutex_);
    closing_ = true;
  }
  WriteNext();
}

void LoadSession::Cancel() {
  {
    MutexLock lock(&mutex_);
    cancelled_ = true;
  }
  context_.TryCancel();
}

void LoadSession::WriteNext() {
  bool write = false;
  bool half_close = false;
  {
    MutexLock lock(&mutex_);
    if (writing_ || done_) return;
    if (!queued_.empty()) {
      writing_request_ = std::move(queued_.front());
      queued_.pop_front();
      writing_ = write = true;
    } else if (closing_ && !writes_done_) {
      writes_done_ = half_close = true;
    }
  }
  if (write) StartWrite(&writing_request_);
  if (half_close) StartWritesDone();
}

void LoadSession::OnWriteDone(bool ok) {
  {
    MutexLock lock(&mutex_);
    writing_ = false;
    // A failed write: the stream has ended; OnDone brings its status. Nothing more is written.
    if (!ok) {
      queued_.clear();
      closing_ = writes_done_ = true;
      return;
    }
  }
  WriteNext();
}

void LoadSession::OnReadDone(bool ok) {
  if (!ok) return;  // the server ended the stream; OnDone follows
  const Clock::time_point now = Clock::now();
  const Clock::time_point due =
      shared_.clock.start + std::chrono::microseconds(update_.timestamp_us());
  const std::int64_t round_trip_us =
      std::chrono::duration_cast<std::chrono::microseconds>(now - due).count();
  std::int64_t answered = 0;
  {
    MutexLock lock(&mutex_);
    bool enrolling = shared_.enrolling.load() > 0;
    if (!sent_while_enrolling_.empty()) {
      enrolling = enrolling || sent_while_enrolling_.front();
      sent_while_enrolling_.pop_front();
    }
    round_trip_.Record(round_trip_us);
    processing_.Record(update_.processing_time_us());
    if (enrolling) round_trip_enrolling_.Record(round_trip_us);
    answered = ++answered_;
    last_update_ = now;
  }
  shared_.answered.fetch_add(1, std::memory_order_relaxed);
  StartRead(&update_);
  if (closed_loop_ && now < shared_.clock.end) SendFrame(answered, now);
}

void LoadSession::OnDone(const grpc::Status& status) {
  MutexLock lock(&mutex_);
  status_ = status;
  done_ = true;
  // Under the lock: once WaitDone sees done_, the session may be destroyed.
  ended_.SignalAll();
}

bool LoadSession::WaitDone(Clock::time_point deadline) {
  MutexLock lock(&mutex_);
  while (!done_ && ended_.WaitUntil(&mutex_, deadline)) {
  }
  return done_;
}

void LoadSession::AddTo(LoadReport& report, Clock::time_point& last_update) const {
  MutexLock lock(&mutex_);
  report.frames_sent += static_cast<std::uint64_t>(sent_);
  report.frames_answered += static_cast<std::uint64_t>(answered_);
  report.round_trip.Merge(round_trip_);
  if (round_trip_.count() > 0) {
    const double p99 = round_trip_.Percentile(99);
    report.worst_session_p99_us = std::max(report.worst_session_p99_us, p99);
    if (p99 > 5000) ++report.sessions_p99_above_5ms;
  }
  report.processing.Merge(processing_);
  report.round_trip_enrolling.Merge(round_trip_enrolling_);
  if (answered_ > 0) ++report.sessions_opened;
  if (cancelled_ && status_.error_code() == grpc::StatusCode::CANCELLED) {
    ++report.sessions_cancelled;
  } else if (!status_.ok()) {
    ++report.sessions_failed;
    ++report.errors[std::string(StatusCodeName(status_.error_code()))];
  }
  last_update = std::max(last_update, last_update_);
}

}  // namespace orbit
