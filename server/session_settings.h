// What a recognition session runs with: the engine and its options, resolved from what the
// device asked for (v1::SessionOptions), the server's defaults and its limits.
#pragma once

#include <cstdint>

#include <grpcpp/grpcpp.h>

#include "api/engines/engine_names.h"
#include "api/image_header.h"
#include "core/descriptor/descriptor.h"
#include "core/engines/product_pipeline.h"
#include "core/engines/recognition_engine.h"
#include "orbit/v1/recognition.pb.h"

namespace orbit::server {

// The server's limits, each refused with RESOURCE_EXHAUSTED when exceeded.
struct ServerLimits {
  int max_sessions = 256;             // concurrent Session streams
  double max_frames_per_second = 60;  // per session, averaged over a 2-second burst allowance
  int max_window = kMaxWindow;        // W a session may ask for (1..kMaxWindow)
  int max_message_bytes = 4 << 20;    // any single request message
  int idle_timeout_seconds = 120;     // a session without a frame for this long is closed
  // window x hmm_states a session running the HMM may ask for: the HMM keeps about 10 bytes per
  // (frame, state, object), so 1024 bounds a session at about 10 MB per 1000 enrolled objects
  // (the defaults, 8 x 8, use 64; the unchecked extreme, 64 x 360, would be 230 MB).
  int max_hmm_cells = 1024;
  // width x height of an uploaded image (Frame.image, View.image), read from its header before
  // decoding (api/image_header.h, which says why 4096 x 4096 by default; CEDD needs far fewer
  // pixels than that). Unchecked, a small compressed file could claim 20000 x 20000 pixels,
  // gigabytes once decoded.
  int max_image_pixels = static_cast<int>(kDefaultMaxImagePixels);
  // Unary calls waiting for a worker, per pool (server/worker_pool.h): beyond it a call is
  // refused RESOURCE_EXHAUSTED at once rather than holding its request (up to
  // max_message_bytes) in a queue the workers may never reach in time.
  int max_queued_calls = 32;
  // Enroll streams: open at once, the bytes of one stream's views together (encoded images can
  // be large; held until the stream ends), and the time one may go without a message.
  int max_enrollments = 4;
  std::int64_t max_enrollment_bytes = std::int64_t{256} << 20;
  int enrollment_idle_timeout_seconds = 30;
  // Session streams one token may hold at once (with --tokens): one device's token cannot take
  // every slot of max_sessions. 0: no per-token limit.
  int max_sessions_per_token = 64;
  // Recognize calls one token may have in progress (queued or running) at once, with --tokens:
  // one token cannot fill the calls' queue (max_queued_calls) while other devices wait.
  // 0: no per-token limit.
  int max_recognize_calls_per_token = 8;
};

struct SessionSettings {
  // The product pipeline's engine and options by default (core/engines/product_pipeline.h; why:
  // docs/results/robustness.md).
  v1::Engine engine = ProductSessionEngine();  // never ENGINE_UNSPECIFIED once resolved
  EngineOptions options = Product().options;
};

// `requested` over `defaults`: a field at 0 / unset keeps the default. INVALID_ARGUMENT for an
// unknown engine, a variant other than the server's, or a value out of range (the message names
// it); RESOURCE_EXHAUSTED for a window above limits.max_window, or for an HMM session whose
// window x hmm_states is above limits.max_hmm_cells.
grpc::Status ResolveSessionSettings(const v1::SessionOptions& requested,
                                    const SessionSettings& defaults, DescriptorVariant variant,
                                    const ServerLimits& limits, SessionSettings* out);

// Every field filled in: what ServerInfo reports as the defaults.
v1::SessionOptions DescribeSettings(const SessionSettings& settings, DescriptorVariant variant);

// The HMM memory rule: OK unless `settings` runs an HMM (api/engines/engine_names.h, RunsHmm) with
// window x hmm_states above limits.max_hmm_cells; then RESOURCE_EXHAUSTED naming both numbers.
// Checked for every session, and for the server's defaults at start-up (server_config.h).
grpc::Status CheckHmmCells(const SessionSettings& settings, const ServerLimits& limits);

}  // namespace orbit::server
