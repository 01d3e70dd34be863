// SessionEnvironment: what every recognition session of a server shares (its Session streams and
// its Recognize calls alike).
#pragma once

#include "server/model_catalogue.h"
#include "server/rejection_calibrator.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/session_registry.h"
#include "server/session_settings.h"
#include "server/worker_pool.h"

namespace orbit::server {

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

}  // namespace orbit::server
