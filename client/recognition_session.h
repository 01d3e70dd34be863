// RecognitionSession: a device's live recognition session (Recognition.Session,
// proto/orbit/v1/recognition.proto). The device pushes frames - an image and the azimuth its
// orientation sensor read - and receives, for every frame and in order, an update with the
// ranked candidates, the decision and the suggested move.
//
// The CEDD of each image is computed here, on the device (core/descriptor/cedd.h), in the server's
// descriptor variant (asked with ServerInfo when the session opens), so only 144 bytes and an
// azimuth travel per frame.
//
// Reconnection: when the stream ends with UNAVAILABLE (the server restarted, the network
// dropped), with a CANCELLED the device did not cause (a server cancelling its calls as it
// shuts down) or with no status at all (UNKNOWN: a load balancer in front of server replicas
// lost the one serving the session; docs/scaling.md), and the session was not closed by the device,
// a new stream is opened with the same options and the session replays the frames still in the
// window - the last W answered frames, whose updates are not delivered again - then every frame not
// yet answered. The server thus rebuilds the same window and the updates continue in order, none
// lost and none repeated, with the frame indices the device was given. Attempts continue for
// RecognitionOptions::reconnect_timeout; after that the session ends with UNAVAILABLE. Frames sent
// before a Reset() and still unanswered when the connection drops are not replayed: the device
// had started over.
//
// Errors: Open() throws RpcError when the server is unreachable or refuses the token.
// Problems the server finds later (bad options, bad frames, rate limits, idle timeout) end the
// session: NextUpdate() then returns nullopt, Push*() throw RpcError with that status, and
// Close() returns it. Bad arguments (empty image, region outside the image) throw
// std::invalid_argument before anything is sent.
//
// Thread safety: Push*, Reset, NextUpdate and Close may be called from any threads; pushes from
// several threads are numbered in the order they are sent. Push blocks while a reconnection
// is in progress. The update callback runs on the session's reader thread: it must not call
// Close() (it may push).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <thread>

#include <opencv2/core.hpp>

#include "client/connection.h"
#include "client/frame_quality.h"
#include "core/base/mutex.h"
#include "core/descriptor/descriptor.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.grpc.pb.h"

namespace orbit {

// What a device asks of a recognition session: the engine and its options (a field left at 0 /
// unset takes the server's default, ServerInfo's session_defaults; the meaning and ranges are
// those of v1::SessionOptions, checked by the server), and how the client library runs it.
struct RecognitionOptions {
  v1::Engine engine = v1::ENGINE_UNSPECIFIED;           // VCI, HMM, both, or a baseline
  int top_k = 0;                                        // candidates per update
  int window = 0;                                       // W: frames the session remembers
  std::optional<double> orientation_weight;             // w of the Hough score, per radian
  int list_length = 0;                                  // N_L: views per retrieval list
  int hmm_states = 0;                                   // HMM sectors per object
  std::optional<double> threshold;                      // Th of the accept rule REJECTION_TH
  v1::Rejection rejection = v1::REJECTION_UNSPECIFIED;  // the accept / unknown rule
  std::optional<double> false_accept_rate;              // REJECTION_CALIBRATED's target, in (0, 1)
  std::optional<double> known_accept_rate;  // REJECTION_CALIBRATED's known share, in [0, 1)
  // The descriptor variant of the frames; unset: the server's. Setting another variant than
  // the server's ends the session with INVALID_ARGUMENT.
  std::optional<DescriptorVariant> variant;

  // How long to keep trying to reopen a session after the connection drops; 0 disables
  // reconnection.
  std::chrono::milliseconds reconnect_timeout{30000};
  // When set, updates are delivered to this callback (on the session's reader thread) instead
  // of to NextUpdate().
  std::function<void(const v1::SessionUpdate&)> on_update;
};

// The `open` message of a session with `options` whose frames are in `variant`: unset fields
// stay unset, so the server fills in its defaults.
v1::SessionOptions ToProtoSessionOptions(const RecognitionOptions& options,
                                         DescriptorVariant variant);

class RecognitionSession {
 public:
  // Asks the server for its variant and defaults, then opens the stream. `connection` must
  // outlive the session. Throws RpcError when ServerInfo fails or the stream cannot start.
  static std::unique_ptr<RecognitionSession> Open(const Connection& connection,
                                                  RecognitionOptions options);

  // Cancels the stream if Close() was not called; updates not yet received are dropped.
  ~RecognitionSession();

  RecognitionSession(const RecognitionSession&) = delete;
  RecognitionSession& operator=(const RecognitionSession&) = delete;

  // Computes the CEDD of `image` (of `region` inside it when given) and sends it with the
  // device azimuth in degrees (any finite value; only differences between frames matter), or
  // none (nullopt) from a device without an orientation sensor: the server then recognises
  // from the descriptors alone (docs/service.md, "Frames without azimuth").
  // `timestamp_us` is echoed in the update; `quality` (client/frame_quality.h), measured here
  // when not given, travels as Frame.quality. Returns the frame's index (0 for the first frame
  // after Open or Reset), which its update carries as frame_index.
  // Throws std::invalid_argument as ExtractCedd does; RpcError when the session has ended.
  std::int64_t Push(const cv::Mat& image, std::optional<double> azimuth_deg,
                    std::optional<cv::Rect> region = std::nullopt,
                    std::optional<std::int64_t> timestamp_us = std::nullopt,
                    std::optional<FrameQuality> quality = std::nullopt)
      ABSL_LOCKS_EXCLUDED(write_mu_);

  // Sends a descriptor computed elsewhere, in variant(). As Push otherwise.
  std::int64_t PushDescriptor(const DescriptorValues& descriptor, std::optional<double> azimuth_deg,
                              std::optional<std::int64_t> timestamp_us = std::nullopt,
                              std::optional<FrameQuality> quality = std::nullopt)
      ABSL_LOCKS_EXCLUDED(write_mu_);

  // Starts over on another object: the server forgets every frame and the next frame gets
  // index 0. Updates of frames pushed before still arrive.
  void Reset() ABSL_LOCKS_EXCLUDED(write_mu_);

  // Blocks until the next update (frame_index in the device's numbering) and returns it, or
  // nullopt once the session has ended and every received update was returned.
  std::optional<v1::SessionUpdate> NextUpdate() ABSL_LOCKS_EXCLUDED(state_mu_);

  // Tells the server no more frames come, waits until every frame pushed has its update (or
  // the session fails) and returns the final status: OK when the server ended the session
  // cleanly. Updates still queued remain readable with NextUpdate(). Idempotent.
  grpc::Status Close() ABSL_LOCKS_EXCLUDED(write_mu_, state_mu_);

  DescriptorVariant variant() const { return variant_; }
  int window() const { return window_size_; }
  // The least time between frames that keeps within the server's frame-rate limit
  // (ServerInfo.limits.max_frames_per_second); 0 when the server states none.
  std::chrono::microseconds min_frame_interval() const { return replay_interval_; }
  // How many times the stream was reopened after a dropped connection.
  int reconnections() const ABSL_LOCKS_EXCLUDED(state_mu_);

 private:
  // A frame sent on the current stream and awaiting its update.
  struct SentFrame {
    std::int64_t index = 0;   // the device's numbering
    std::uint64_t epoch = 0;  // Reset() count when it was pushed
    bool deliver = true;      // false for a window frame replayed after a reconnection
    v1::Frame frame;
  };

  using Stream = grpc::ClientReaderWriter<v1::SessionRequest, v1::SessionUpdate>;

  RecognitionSession(const Connection& connection, RecognitionOptions options,
                     const v1::ServerInfoResponse& info);
  // Starts a stream and sends the open message; false when the write failed (the stream's
  // Finish() says why).
  bool StartStream() ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mu_);
  std::int64_t Send(v1::Frame frame) ABSL_LOCKS_EXCLUDED(write_mu_);
  // The reader thread's loop, from `stream`, the stream Open() started. Only this thread
  // replaces stream_ afterwards (Reopen), so it reads from the stream it holds without a lock.
  void ReadUpdates(Stream* stream) ABSL_LOCKS_EXCLUDED(write_mu_);
  void Deliver(v1::SessionUpdate update) ABSL_LOCKS_EXCLUDED(state_mu_);
  // Opens a new stream and replays; OK on success, else the status to end the session with.
  grpc::Status Reopen() ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mu_) ABSL_LOCKS_EXCLUDED(state_mu_);
  void End(const grpc::Status& status) ABSL_LOCKS_EXCLUDED(state_mu_);
  // Throws RpcError when the session has ended, std::logic_error after Close().
  void ThrowIfEnded(const char* call) const ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mu_, state_mu_);

  const Connection& connection_;
  const RecognitionOptions options_;
  const DescriptorVariant variant_;
  const int window_size_;
  const std::chrono::microseconds replay_interval_;  // paces replays to the server's frame limit
  std::unique_ptr<v1::Recognition::Stub> stub_;

  // Serialises writes to the stream and its replacement.
  Mutex write_mu_;
  std::unique_ptr<grpc::ClientContext> context_ ABSL_GUARDED_BY(write_mu_);
  std::unique_ptr<Stream> stream_ ABSL_GUARDED_BY(write_mu_);
  // WritesDone sent (or to send after a reconnection).
  bool closing_ ABSL_GUARDED_BY(write_mu_) = false;

  mutable Mutex state_mu_ ABSL_ACQUIRED_AFTER(write_mu_);
  CondVar state_changed_;
  // In the order the server answers them.
  std::deque<SentFrame> in_flight_ ABSL_GUARDED_BY(state_mu_);
  // The last window_size_ answered frames of this epoch.
  std::deque<SentFrame> window_ ABSL_GUARDED_BY(state_mu_);
  std::deque<v1::SessionUpdate> updates_ ABSL_GUARDED_BY(state_mu_);
  std::int64_t next_index_ ABSL_GUARDED_BY(state_mu_) = 0;
  std::uint64_t epoch_ ABSL_GUARDED_BY(state_mu_) = 0;
  int reconnections_ ABSL_GUARDED_BY(state_mu_) = 0;
  bool ended_ ABSL_GUARDED_BY(state_mu_) = false;
  bool cancelled_ ABSL_GUARDED_BY(state_mu_) = false;
  grpc::Status final_status_ ABSL_GUARDED_BY(state_mu_);

  std::thread reader_;
};

}  // namespace orbit
