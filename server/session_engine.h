// SessionEngine: the recognition state of one session, behind the engine the device chose:
// one engine of core/engines/recognition_engine.h, or VCI and the HMM together (ENGINE_VCI_HMM).
//
// The combination runs both engines on every frame and ranks objects by the mean of their two
// scores (an object missing from one engine's ranking counts 0 there; both rankings are taken
// deeper than top_k so that this is rare). Its decision is the decision of whichever engine
// ranks the combined winner first (VCI's when both do), UNDECIDED when neither does; its
// suggested move is VCI's.
//
// Not thread-safe: one session, one thread at a time.
#pragma once

#include <memory>
#include <vector>

#include "core/engines/recognition_engine.h"
#include "core/decision/rejection_calibration.h"
#include "core/index/view_index.h"
#include "server/session_settings.h"

namespace orbit::server {

class SessionEngine {
 public:
  // REQUIRES: settings came from ResolveSessionSettings.
  explicit SessionEngine(const SessionSettings& settings);

  // One frame in, one update out, decided with `calibration` (the calibrated rule's; may be
  // null). Throws std::invalid_argument as RecognitionEngine::Observe (the session's state is
  // then unchanged).
  FrameUpdate Observe(const std::shared_ptr<const ViewIndexSnapshot>& index,
                      const std::shared_ptr<const RejectionCalibration>& calibration,
                      const QueryFrame& frame);

  void Reset();

 private:
  int top_k_;
  std::vector<std::unique_ptr<RecognitionEngine>> engines_;
};

// What the first frame of a session with `defaults` computes on a new snapshot for every
// session after it: the change since the previous snapshot and, for an HMM, the sector table
// (about 1 ms at 1000 objects, during which the frames of every other session wait on a
// one-core server). For ModelCatalogue::PrepareSnapshotsWith.
ViewIndex::SnapshotPreparation PrepareForSessions(const SessionSettings& defaults);

}  // namespace orbit::server
