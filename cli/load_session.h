// LoadSession: one recognition session of `orbit loadtest` - a Recognition.Session stream that
// shows a turntable's views frame after frame - and what its frames measured.
//
// It drives the generated stub on gRPC's callback API rather than client/recognition_session.h,
// whose session reads on a thread of its own and writes synchronously. In a closed loop of 64
// HMM sessions against a server pinned to one core, that session cost the generator, pinned to
// another, about what a frame cost the server and nearly all of its core: a server made faster
// would have been measured at the generator's speed. This one costs markedly less (the
// generator's CPU per frame: docs/results/load.md, "The table at B0"). (At 8 sessions
// both cost about the same, mostly the kernel's: a send and a wake-up for one small message
// each way.) The library's session also replays frames after a dropped
// connection, which would hide the errors a load test is to count, and sends descriptors only
// (--image-frames sends encoded images). The connection (token, TLS) and the open message
// (ToProtoSessionOptions) are the client library's.
//
// Frames may be sent from any thread (an open loop's scheduler) or from the update reaction
// (a closed loop); they are written in order, one write in flight. The round trip of a frame
// counts from the time it was due, carried in its timestamp_us and echoed by the server.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "cli/latency_histogram.h"
#include "cli/load_report.h"
#include "client/connection.h"
#include "core/base/mutex.h"
#include "core/descriptor/descriptor.h"
#include "orbit/v1/recognition.grpc.pb.h"

namespace orbit {

// One view of an object, as a session sends it.
struct TurntableView {
  std::string cedd, appearance;  // the view's descriptor as a frame carries it
  std::string encoded;           // the encoded image file, for image frames
  double azimuth = 0;            // degrees
};

// The load's time span, shared by every session.
struct LoadClock {
  using Clock = std::chrono::steady_clock;
  Clock::time_point start;  // frame round trips count from here (timestamp_us 0)
  Clock::time_point end;    // no frame is sent at or after this
};

// What a session shares with the rest of the load.
struct LoadShared {
  const LoadClock& clock;
  // Enrollments running now (frames sent or answered meanwhile are counted apart).
  const std::atomic<int>& enrolling;
  // Updates received by every session, for the progress line.
  std::atomic<std::uint64_t>& answered;
};

class LoadSession final : public grpc::ClientBidiReactor<v1::SessionRequest, v1::SessionUpdate> {
 public:
  using Clock = std::chrono::steady_clock;

  // Session `number` shows `turntable` (not empty), from a view of its own, with a compass
  // offset of its own. In a closed loop each update sends the next frame until clock.end.
  LoadSession(int number, const std::vector<TurntableView>& turntable, bool image_frames,
              bool closed_loop, const LoadShared& shared);

  // Opens the stream with `open` as its first message. `connection` and `stub` must outlive
  // the stream.
  void Start(v1::Recognition::Stub& stub, const Connection& connection,
             const v1::SessionOptions& open) ABSL_LOCKS_EXCLUDED(mutex_);

  // Queues frame k (the k-th view from the session's first, the azimuth advancing a lap every
  // turntable.size() frames) whose round trip counts from `due`. False once the stream has
  // ended or CloseWrites was called. Any thread.
  bool SendFrame(std::int64_t k, Clock::time_point due) ABSL_LOCKS_EXCLUDED(mutex_);

  // No more frames: the stream is half-closed once the queued frames are written; the server
  // then answers them and ends the stream.
  void CloseWrites() ABSL_LOCKS_EXCLUDED(mutex_);

  // Ends the stream now; frames not yet answered stay unanswered, and the CANCELLED status
  // this causes is counted as a cancelled session, not as an error of the server.
  void Cancel() ABSL_LOCKS_EXCLUDED(mutex_);

  // Waits until the stream has ended (OnDone) or `deadline` passes; true when it has ended.
  // The session may be destroyed only after it has ended.
  bool WaitDone(Clock::time_point deadline) ABSL_LOCKS_EXCLUDED(mutex_);

  // Adds this session's frames, round trips, processing times and final status to `report`,
  // and raises `last_update` to its last update's arrival. REQUIRES: the stream has ended.
  void AddTo(LoadReport& report, Clock::time_point& last_update) const ABSL_LOCKS_EXCLUDED(mutex_);

  void OnWriteDone(bool ok) ABSL_LOCKS_EXCLUDED(mutex_) override;
  void OnReadDone(bool ok) ABSL_LOCKS_EXCLUDED(mutex_) override;
  void OnWritesDoneDone(bool) override {}
  void OnDone(const grpc::Status& status) ABSL_LOCKS_EXCLUDED(mutex_) override;

 private:
  // Starts the next write (or the half-close) if none is in flight. Never called with mutex_
  // held: a reaction may run inside a Start* call.
  void WriteNext() ABSL_LOCKS_EXCLUDED(mutex_);

  const std::vector<TurntableView>& turntable_;
  const std::size_t first_view_;
  const double compass_offset_;
  const bool image_frames_;
  const bool closed_loop_;
  const LoadShared shared_;

  grpc::ClientContext context_;
  v1::SessionUpdate update_;  // the read in flight; touched by the read reactions only

  mutable Mutex mutex_;
  CondVar ended_;
  // Frames (and first the open) not yet written.
  std::deque<v1::SessionRequest> queued_ ABSL_GUARDED_BY(mutex_);
  // The write in flight: gRPC reads it, unlocked, until OnWriteDone.
  v1::SessionRequest writing_request_ ABSL_GUARDED_BY(mutex_);
  bool writing_ ABSL_GUARDED_BY(mutex_) = false;
  bool closing_ ABSL_GUARDED_BY(mutex_) = false;      // CloseWrites called
  bool writes_done_ ABSL_GUARDED_BY(mutex_) = false;  // the half-close was started
  bool done_ ABSL_GUARDED_BY(mutex_) = false;         // OnDone called
  bool cancelled_ ABSL_GUARDED_BY(mutex_) = false;    // Cancel called
  grpc::Status status_ ABSL_GUARDED_BY(mutex_);
  std::int64_t sent_ ABSL_GUARDED_BY(mutex_) = 0;
  std::int64_t answered_ ABSL_GUARDED_BY(mutex_) = 0;
  // One per frame sent and not yet answered.
  std::deque<bool> sent_while_enrolling_ ABSL_GUARDED_BY(mutex_);
  LatencyHistogram round_trip_ ABSL_GUARDED_BY(mutex_);
  LatencyHistogram processing_ ABSL_GUARDED_BY(mutex_);
  LatencyHistogram round_trip_enrolling_ ABSL_GUARDED_BY(mutex_);
  Clock::time_point last_update_ ABSL_GUARDED_BY(mutex_);
};

}  // namespace orbit
