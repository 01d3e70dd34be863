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
#include <mutex>
#include <optional>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/recognition.grpc.pb.h"
#include "server/frame_rate_limit.h"
#include "server/model_catalogue.h"
#include "server/rejection_calibrator.h"
#include "server/refusal_reason.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/session_engine.h"
#include "server/session_registry.h"
#include "server/session_settings.h"
#include "server/worker_pool.h"

namespace orbit::server {

// What every session of a server shares.
struct SessionEnvironment {
  ModelCatalogue& catalogue;
  RejectionCalibrator& calibrator;  // the calibrated rule's thresholds for the catalogue's index
  WorkerPool& pool;       // Recognize calls of descriptors (a session's run in its reactions)
  WorkerPool& bulk_pool;  // image frames (decoding), so they never delay descriptor frames
  SessionRegistry& registry;
  const ServerLimits& limits;
  const SessionSettings& defaults;
  ServerMetrics& metrics;
  const ServingGate& gate;  // closed until the index is loaded: sessions refused UNAVAILABLE
};

class SessionReactor final
    : public grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate>,
      public RegisteredSession {
 public:
  // Registers with the registry (ending the stream at once with its refusal, if any) and
  // reads the first request. `context` is the call's; it outlives the reactor.
  SessionReactor(const SessionEnvironment& environment, grpc::CallbackServerContext* context);

  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnDone() override;

  // Ends the stream with `status` once the frame in hand, if any, is processed. An update the
  // device has not taken for kStalledWrite is abandoned: the call is cancelled, so a device that
  // stops reading cannot hold its session slot (its window full, the write would never end).
  void Close(const grpc::Status& status) override;
  std::chrono::steady_clock::time_point last_activity() const override;

 private:
  using Clock = std::chrono::steady_clock;

  // REQUIRES: mutex_ held. Each handles the request just read.
  void HandleOpen(const v1::SessionOptions& options);
  // `previous_read_done`: when the read before this frame's completed (the rate limit counts
  // the time the server held the stream since as the device's, not as a burst).
  // Returns true when the caller must Process() the frame in request_ once it has released
  // mutex_.
  bool HandleFrame(Clock::time_point received, Clock::time_point previous_read_done);
  void ReadNext();
  void FinishOnce(const grpc::Status& status);
  // FinishOnce with a refusal, counted under `reason` unless the stream has already finished.
  void Refuse(const grpc::Status& status, RefusalReason reason);

  // Runs in the read's reaction (descriptor frames) or on the bulk workers (image frames).
  void Process(v1::Frame frame, Clock::time_point received);

  // A write not taken by the device for this long, when the session is closed, is abandoned.
  static constexpr std::chrono::seconds kStalledWrite{1};

  const SessionEnvironment env_;
  grpc::CallbackServerContext* const context_;
  // Recursive: a reaction may run inside a Start* call. Taken after the registry's lock (the
  // registry calls Close with it held), never before it.
  std::recursive_mutex mutex_;
  v1::SessionRequest request_;
  v1::SessionUpdate update_;
  std::unique_ptr<RecognitionEngine> engine_;  // set by the open request
  FrameMetrics frame_metrics_;             // of the engine_'s engine, set with it
  bool registered_ = false;
  bool busy_ = false;      // a frame is being processed or its update written
  std::optional<Clock::time_point> write_started_;  // while an update is being written
  bool finished_ = false;  // Finish has been called
  std::optional<grpc::Status> pending_close_;  // Close() while busy: applied when idle
  RefusalReason pending_reason_ = RefusalReason::kInternal;  // of pending_close_
  FrameRateLimit rate_limit_;
  Clock::time_point read_started_;        // when the outstanding read was started
  Clock::time_point previous_read_done_;  // when the read before it completed
  std::atomic<Clock::rep> last_activity_;
};

}  // namespace orbit::server
