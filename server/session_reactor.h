// SessionReactor: one Recognition.Session stream (proto/orbit/v1/recognition.proto).
//
// Frames are handled strictly one after another: read a request, process it (engine update),
// write its update, then read the next, so there is never more than one read and one write in
// flight. A descriptor frame is processed in the read's reaction, on gRPC's thread: handing it
// to a worker thread and the update back cost two thread wake-ups per frame, more CPU than the
// HMM's work on 100 objects (docs/results/load.md). An image frame is decoded on the bulk
// workers, so that a large image never delays another session's descriptor frames. Any bad
// request ends this stream alone with the status docs/design.md#service-behaviour names.
//
// Lifetime: created by RecognitionService for each call, deleted in OnDone.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"
#include "orbit/v1/recognition.grpc.pb.h"
#include "server/frame_answer.h"
#include "server/frame_rate_limit.h"
#include "server/model_catalogue.h"
#include "server/refusal_reason.h"
#include "server/rejection_calibrator.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/session_engine.h"
#include "server/session_environment.h"
#include "server/session_registry.h"
#include "server/session_settings.h"
#include "server/worker_pool.h"

namespace orbit::server {

class SessionReactor final : public grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate>,
                             public RegisteredSession {
 public:
  // Registers with the registry (ending the stream at once with its refusal, if any) and
  // reads the first request. `context` is the call's; it outlives the reactor. `token`: the name
  // of the caller's token, for the per-token limit ("" without access control).
  SessionReactor(const SessionEnvironment& environment, grpc::CallbackServerContext* context,
                 const std::string& token) ABSL_LOCKS_EXCLUDED(mutex_);

  void OnReadDone(bool ok) ABSL_LOCKS_EXCLUDED(mutex_) override;
  void OnWriteDone(bool ok) ABSL_LOCKS_EXCLUDED(mutex_) override;
  void OnDone() ABSL_LOCKS_EXCLUDED(mutex_) override;

  // Ends the stream with `status` once the frame in hand, if any, is processed. An update the
  // device has not taken for kStalledWrite is abandoned: the call is cancelled, so a device that
  // stops reading cannot hold its session slot (its window full, the write would never end).
  void Close(const grpc::Status& status) ABSL_LOCKS_EXCLUDED(mutex_) override;
  std::chrono::steady_clock::time_point last_activity() const override;

 private:
  using Clock = std::chrono::steady_clock;

  // What to do on the stream once mutex_ is released. The reactor never calls into the stream
  // (StartRead, StartWrite, Finish, TryCancel) with mutex_ held: gRPC may run a reaction, which
  // takes mutex_, inside such a call. Decided under mutex_, done by Perform() after it; a call
  // is the last thing its path does with the reactor, as the reactor may be deleted (OnDone)
  // on another thread as soon as the call is made. Except after StartRead: kRead is decided
  // only in a reaction or the constructor, and gRPC holds the reactor until they return.
  struct StreamOp {
    enum class Kind { kNone, kRead, kWrite, kFinish, kCancel };
    Kind kind = Kind::kNone;
    grpc::Status status;  // kFinish's
  };

  // A frame to process: taken from the request under mutex_, processed without it. The session
  // is used only by the frame in hand (busy_), so never concurrently.
  struct FrameTask {
    v1::Frame frame;
    Clock::time_point received;
    OpenedSession* session = nullptr;
  };

  // Each handles the request just read.
  StreamOp HandleOpen(const v1::SessionOptions& options) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // `previous_read_done`: when the read before this frame's completed (the rate limit counts
  // the time the server held the stream since as the device's, not as a burst). Sets `task`
  // when the frame is to be processed (the caller does so once it has released mutex_).
  StreamOp HandleFrame(Clock::time_point received, Clock::time_point previous_read_done,
                       std::optional<FrameTask>* task) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // The next read, or the pending close.
  StreamOp ReadNext() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  StreamOp FinishOnce(const grpc::Status& status) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // FinishOnce with a refusal, counted under `reason` unless the stream has already finished.
  StreamOp Refuse(const grpc::Status& status, RefusalReason reason)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);

  void Perform(const StreamOp& op) ABSL_LOCKS_EXCLUDED(mutex_);
  // Once a read decided by ReadNext has started: the close that came meanwhile, if any.
  StreamOp AfterReadStarted() ABSL_LOCKS_EXCLUDED(mutex_);

  // Runs in the read's reaction (descriptor frames) or on the bulk workers (image frames).
  void Process(FrameTask task) ABSL_LOCKS_EXCLUDED(mutex_);
  // Instead of Process, when the server's shutdown finds the image frame still queued: ends the
  // stream with the close pending (the shutdown's), unanswered.
  void Abandon() ABSL_LOCKS_EXCLUDED(mutex_);

  // A write not taken by the device for this long, when the session is closed, is abandoned.
  static constexpr std::chrono::seconds kStalledWrite{1};

  const SessionEnvironment env_;
  grpc::CallbackServerContext* const context_;
  // Taken after the registry's lock (the registry calls Close with it held), never before it.
  Mutex mutex_ ABSL_ACQUIRED_AFTER(env_.registry.mutex());
  // The request being read and the update being written: gRPC fills and reads them, unlocked,
  // while the read or the write is outstanding, when no reaction touches them.
  v1::SessionRequest request_ ABSL_GUARDED_BY(mutex_);
  v1::SessionUpdate update_ ABSL_GUARDED_BY(mutex_);
  // Set by the open request: its engine is null until then.
  OpenedSession session_ ABSL_GUARDED_BY(mutex_);
  bool registered_ ABSL_GUARDED_BY(mutex_) = false;
  // A frame is being processed or its update written.
  bool busy_ ABSL_GUARDED_BY(mutex_) = false;
  // Reads decided and not yet known to have started (StreamOp::kRead until AfterReadStarted).
  int reads_starting_ ABSL_GUARDED_BY(mutex_) = 0;
  // While an update is being written.
  std::optional<Clock::time_point> write_started_ ABSL_GUARDED_BY(mutex_);
  bool finished_ ABSL_GUARDED_BY(mutex_) = false;  // Finish has been (or is being) called
  // Close() while busy_ or while a read is starting: applied as soon as neither holds.
  std::optional<grpc::Status> pending_close_ ABSL_GUARDED_BY(mutex_);
  RefusalReason pending_reason_ ABSL_GUARDED_BY(mutex_) = RefusalReason::kInternal;
  FrameRateLimit rate_limit_ ABSL_GUARDED_BY(mutex_);
  Clock::time_point read_started_ ABSL_GUARDED_BY(mutex_);  // when the outstanding read began
  // When the read before it completed.
  Clock::time_point previous_read_done_ ABSL_GUARDED_BY(mutex_);
  std::atomic<Clock::rep> last_activity_;
};

}  // namespace orbit::server
