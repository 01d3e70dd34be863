#include "client/recognition_session.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "api/conversion.h"
#include "client/models_client.h"
#include "client/rpc_error.h"
#include "core/descriptor/cedd.h"

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;

// A stream end that a new stream may cure: the connection dropped or the server went away
// (UNAVAILABLE), the server cancelled the call as it shut down (CANCELLED; the device's own
// cancellation is told apart by the caller), or the stream ended with no status at all
// (UNKNOWN "No status received": a balancer between device and server lost the server under
// it; an Orbit server itself always ends a session with a status of its own, never UNKNOWN).
bool IsTransient(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::UNAVAILABLE ||
         status.error_code() == grpc::StatusCode::CANCELLED ||
         status.error_code() == grpc::StatusCode::UNKNOWN;
}

// The window the server will keep: the session's own, else the server's default, else the
// largest the server allows (replaying more frames than the window changes nothing). An Orbit
// server reports both in ServerInfo; one that reports neither gets the last frame replayed.
int WindowSize(const RecognitionOptions& options, const v1::ServerInfoResponse& info) {
  if (options.window > 0) return options.window;
  if (info.session_defaults().window() > 0) return info.session_defaults().window();
  return std::max(1, info.limits().max_window());
}

std::chrono::microseconds ReplayInterval(const v1::ServerInfoResponse& info) {
  const double max_fps = info.limits().max_frames_per_second();
  if (!(max_fps > 0)) return std::chrono::microseconds(0);
  return std::chrono::microseconds(static_cast<std::int64_t>(1e6 / max_fps) + 1);
}

}  // namespace

v1::SessionOptions ToProtoSessionOptions(const RecognitionOptions& options,
                                         DescriptorVariant variant) {
  v1::SessionOptions open;
  open.set_engine(options.engine);
  open.set_top_k(options.top_k);
  open.set_window(options.window);
  if (options.orientation_weight) open.set_orientation_weight(*options.orientation_weight);
  open.set_list_length(options.list_length);
  open.set_hmm_states(options.hmm_states);
  if (options.threshold) open.set_threshold(*options.threshold);
  open.set_rejection(options.rejection);
  if (options.false_accept_rate) open.set_false_accept_rate(*options.false_accept_rate);
  if (options.known_accept_rate) open.set_known_accept_rate(*options.known_accept_rate);
  open.set_variant(ToProtoVariant(variant));
  return open;
}

std::unique_ptr<RecognitionSession> RecognitionSession::Open(const Connection& connection,
                                                             RecognitionOptions options) {
  const v1::ServerInfoResponse info = ModelsClient(connection).ServerInfo();
  std::unique_ptr<RecognitionSession> session(
      new RecognitionSession(connection, std::move(options), info));
  Stream* stream = nullptr;
  {
    MutexLock write_lock(&session->write_mu_);
    if (!session->StartStream()) {
      const grpc::Status status = session->stream_->Finish();
      ThrowIfError("Session", status.ok() ? grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                                         "the server ended the session at once")
                                          : status);
    }
    stream = session->stream_.get();
  }
  session->reader_ = std::thread(&RecognitionSession::ReadUpdates, session.get(), stream);
  return session;
}

RecognitionSession::RecognitionSession(const Connection& connection, RecognitionOptions options,
                                       const v1::ServerInfoResponse& info)
    : connection_(connection),
      options_(std::move(options)),
      variant_(options_.variant.value_or(FromProtoVariant(info.variant()))),
      window_size_(WindowSize(options_, info)),
      replay_interval_(ReplayInterval(info)),
      stub_(v1::Recognition::NewStub(connection.channel())) {}

RecognitionSession::~RecognitionSession() {
  if (!reader_.joinable()) return;
  {
    MutexLock state_lock(&state_mu_);
    cancelled_ = true;  // stops a reconnection in progress
  }
  {
    MutexLock write_lock(&write_mu_);
    context_->TryCancel();
  }
  reader_.join();
}

bool RecognitionSession::StartStream() {
  stream_.reset();  // before its context
  context_ = std::make_unique<grpc::ClientContext>();
  connection_.PrepareStreamingCall(*context_);
  stream_ = stub_->Session(context_.get());
  v1::SessionRequest open;
  *open.mutable_open() = ToProtoSessionOptions(options_, variant_);
  return stream_->Write(open);
}

std::int64_t RecognitionSession::Push(const cv::Mat& image, std::optional<double> azimuth_deg,
                                      std::optional<cv::Rect> region,
                                      std::optional<std::int64_t> timestamp_us,
                                      std::optional<FrameQuality> quality) {
  // Measured here when the caller did not: the server's accept / unknown rule allows noisy and
  // blurred frames what noise and blur add (core/decision/quality_allowance.h) only when it knows
  // them.
  if (!quality) quality = MeasureFrameQuality(image, region);
  return PushDescriptor(ExtractCedd(image, variant_, region).values, azimuth_deg, timestamp_us,
                        quality);
}

std::int64_t RecognitionSession::PushDescriptor(const DescriptorValues& descriptor,
                                                std::optional<double> azimuth_deg,
                                                std::optional<std::int64_t> timestamp_us,
                                                std::optional<FrameQuality> quality) {
  v1::Frame frame;
  SetWireDescriptor(descriptor, variant_, frame.mutable_cedd(), frame.mutable_appearance());
  if (azimuth_deg) frame.set_azimuth_deg(*azimuth_deg);
  if (timestamp_us) frame.set_timestamp_us(*timestamp_us);
  if (quality) *frame.mutable_quality() = ToProtoFrameQuality(*quality);
  return Send(std::move(frame));
}

std::int64_t RecognitionSession::Send(v1::Frame frame) {
  MutexLock write_lock(&write_mu_);
  v1::SessionRequest request;
  std::int64_t index = 0;
  {
    MutexLock state_lock(&state_mu_);
    ThrowIfEnded("Push");
    index = next_index_++;
    *request.mutable_frame() = frame;
    in_flight_.push_back(SentFrame{index, epoch_, true, std::move(frame)});
  }
  // A failed write means the stream has ended: the reader thread sees it too, and either
  // reconnects, replaying this frame, or ends the session.
  stream_->Write(request);
  return index;
}

void RecognitionSession::Reset() {
  MutexLock write_lock(&write_mu_);
  {
    MutexLock state_lock(&state_mu_);
    ThrowIfEnded("Reset");
    ++epoch_;
    next_index_ = 0;
    window_.clear();
  }
  v1::SessionRequest request;
  request.mutable_reset();
  stream_->Write(request);
}

std::optional<v1::SessionUpdate> RecognitionSession::NextUpdate() {
  MutexLock state_lock(&state_mu_);
  while (updates_.empty() && !ended_) state_changed_.Wait(&state_mu_);
  if (updates_.empty()) return std::nullopt;
  v1::SessionUpdate update = std::move(updates_.front());
  updates_.pop_front();
  return update;
}

grpc::Status RecognitionSession::Close() {
  {
    MutexLock write_lock(&write_mu_);
    if (!closing_) {
      closing_ = true;
      stream_->WritesDone();
    }
  }
  if (reader_.joinable()) reader_.join();
  MutexLock state_lock(&state_mu_);
  return final_status_;
}

int RecognitionSession::reconnections() const {
  MutexLock state_lock(&state_mu_);
  return reconnections_;
}

void RecognitionSession::ReadUpdates(Stream* stream) {
  for (;;) {
    v1::SessionUpdate update;
    while (stream->Read(&update)) Deliver(std::move(update));

    MutexLock write_lock(&write_mu_);
    grpc::Status status = stream_->Finish();
    bool unanswered = false;
    bool cancelled = false;
    {
      MutexLock state_lock(&state_mu_);
      cancelled = cancelled_;
      const std::uint64_t epoch = epoch_;
      unanswered = std::any_of(in_flight_.begin(), in_flight_.end(),
                               [epoch](const SentFrame& f) { return f.epoch == epoch; });
    }
    // A device that has closed its side only needs the stream back for frames still owed.
    const bool reconnect = IsTransient(status) && !cancelled &&
                           options_.reconnect_timeout.count() > 0 && (!closing_ || unanswered);
    if (reconnect) {
      status = Reopen();
      if (status.ok()) {
        stream = stream_.get();
        continue;
      }
    }
    End(status);
    return;
  }
}

void RecognitionSession::Deliver(v1::SessionUpdate update) {
  {
    MutexLock state_lock(&state_mu_);
    // The server answers every frame once, in order (recognition.proto); an update beyond the
    // frames sent would break that contract and is ignored.
    if (in_flight_.empty()) return;
    SentFrame sent = std::move(in_flight_.front());
    in_flight_.pop_front();
    if (!sent.deliver) return;  // a replayed window frame: its update was delivered before
    update.set_frame_index(sent.index);
    if (sent.epoch == epoch_) {
      window_.push_back(std::move(sent));
      if (window_.size() > static_cast<std::size_t>(window_size_)) window_.pop_front();
    }
    if (!options_.on_update) {
      updates_.push_back(std::move(update));
      state_changed_.SignalAll();
      return;
    }
  }
  options_.on_update(update);
}

grpc::Status RecognitionSession::Reopen() {
  const Clock::time_point deadline = Clock::now() + options_.reconnect_timeout;
  grpc::Status last(grpc::StatusCode::UNAVAILABLE, "connection lost");
  while (Clock::now() < deadline) {
    {
      MutexLock state_lock(&state_mu_);
      if (cancelled_) return grpc::Status(grpc::StatusCode::CANCELLED, "session cancelled");
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (!connection_.WaitForConnected(
            std::clamp(left, std::chrono::milliseconds(1), std::chrono::milliseconds(200)))) {
      continue;
    }

    // What the new stream must carry: the window (updates already delivered), then every frame
    // of this epoch still unanswered.
    std::vector<v1::SessionRequest> replay;
    {
      MutexLock state_lock(&state_mu_);
      std::deque<SentFrame> again;
      for (const SentFrame& f : window_) {
        again.push_back(SentFrame{f.index, f.epoch, false, f.frame});
      }
      for (SentFrame& f : in_flight_) {
        if (f.deliver && f.epoch == epoch_) again.push_back(std::move(f));
      }
      in_flight_ = std::move(again);
      for (const SentFrame& f : in_flight_) *replay.emplace_back().mutable_frame() = f.frame;
    }

    bool written = StartStream();
    for (std::size_t i = 0; written && i < replay.size(); ++i) {
      if (i > 0) std::this_thread::sleep_for(replay_interval_);
      written = stream_->Write(replay[i]);
    }
    if (written) {
      if (closing_) stream_->WritesDone();
      MutexLock state_lock(&state_mu_);
      ++reconnections_;
      return grpc::Status::OK;
    }
    last = stream_->Finish();
    if (!IsTransient(last)) return last;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return grpc::Status(grpc::StatusCode::UNAVAILABLE,
                      "connection lost and not restored within " +
                          std::to_string(options_.reconnect_timeout.count()) +
                          " ms: " + last.error_message());
}

void RecognitionSession::ThrowIfEnded(const char* call) const {
  if (ended_) {
    throw RpcError("Session", final_status_.ok()
                                  ? grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                                                 "the session has ended")
                                  : final_status_);
  }
  if (closing_) throw std::logic_error(std::string("RecognitionSession: ") + call + " after Close");
}

void RecognitionSession::End(const grpc::Status& status) {
  MutexLock state_lock(&state_mu_);
  ended_ = true;
  final_status_ = status;
  state_changed_.SignalAll();
}

}  // namespace orbit
