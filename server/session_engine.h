// The engine of one session: the registry's engine (core/engines/engine_registry.h) that the
// session's resolved settings name, and what every session's first frame on a new snapshot would
// compute, computed once for all of them.
#pragma once

#include <memory>

#include "core/engines/recognition_engine.h"
#include "core/index/view_index.h"
#include "server/session_settings.h"

namespace orbit::server {

// REQUIRES: settings came from ResolveSessionSettings (the engine is one the build knows).
std::unique_ptr<RecognitionEngine> CreateSessionEngine(const SessionSettings& settings);

// What the first frame of a session with `defaults` computes on a new snapshot for every
// session after it: the change since the previous snapshot and what the engine shares
// (PrepareSnapshot: the HMM's sector table), during which the frames of every other session
// would otherwise wait. For ModelCatalogue::PrepareSnapshotsWith.
ViewIndex::SnapshotPreparation PrepareForSessions(const SessionSettings& defaults);

}  // namespace orbit::server
