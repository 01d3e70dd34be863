// SessionReactor: one Recognition.Session stream (proto/orbit/v1/recognition.proto).
//
// Frames are handled strictly one after another: read a request, process it on the worker
// pool (decode, engine update), write its update, then read the next. So there is never more
// than one read and one write in flight, reactions stay short, and engine work never runs on a
// gRPC thread. Any bad request ends this stream alone with the status SPEC.md names.
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
#include "server/session_engine.h"
#include "server/session_registry.h"
#include "server/session_settings.h"
#include "server/worker_pool.h"

namespace orbit::server {

// What every session of a server shares.
struct SessionEnvironment {
  ModelCatalogue& catalogue;
  WorkerPool& pool;       // descriptor frames
  WorkerPool& bulk_pool;  // image frames (decoding), so they never delay descriptor frames
  SessionRegistry& registry;
  const ServerLimits& limits;
  const SessionSettings& defaults;
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
  void HandleFrame(Clock::time_point received, Clock::time_point previous_read_done);
  void ReadNext();
  void FinishOnce(const grpc::Status& status);

  // Runs on the worker pool.
  void Process(v1::Frame frame, Clock::time_point received);

  // A write not taken by the device for this long, when the session is closed, is abandoned.
  static constexpr std::chrono::seconds kStalledWrite{1};

  const SessionEnvironment env_;
  grpc::CallbackServerContext* const context_;
  std::recursive_mutex mutex_;  // recursive: a reaction may run inside a Start* call
  v1::SessionRequest request_;
  v1::SessionUpdate update_;
  std::unique_ptr<SessionEngine> engine_;  // set by the open request
  bool registered_ = false;
  bool busy_ = false;      // a frame is being processed or its update written
  std::optional<Clock::time_point> write_started_;  // while an update is being written
  bool finished_ = false;  // Finish has been called
  std::optional<grpc::Status> pending_close_;  // Close() while busy: applied when idle
  FrameRateLimit rate_limit_;
  Clock::time_point read_started_;        // when the outstanding read was started
  Clock::time_point previous_read_done_;  // when the read before it completed
  std::atomic<Clock::rep> last_activity_;
};

}  // namespace orbit::server
