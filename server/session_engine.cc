#include "server/session_engine.h"

#include <string>

#include "api/engines/engine_names.h"
#include "core/engines/engine_registry.h"

namespace orbit::server {

std::unique_ptr<RecognitionEngine> CreateSessionEngine(const SessionSettings& settings) {
  return CreateEngine(SessionEngineName(settings.engine), settings.options);
}

ViewIndex::SnapshotPreparation PrepareForSessions(const SessionSettings& defaults) {
  return [engine = SessionEngineName(defaults.engine), options = defaults.options](
             const ViewIndexSnapshot& next, const ViewIndexSnapshot& previous) {
    next.ChangeSince(previous);
    PrepareSnapshot(engine, options, next);
  };
}

}  // namespace orbit::server
