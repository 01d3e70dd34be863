#include "server/session_engine.h"

#include <algorithm>
#include <unordered_map>

#include "api/engine_names.h"
#include "core/engines/sector_similarity_table.h"

namespace orbit::server {
namespace {

// How deep each engine ranks when two are combined.
constexpr int kCombinedDepth = 32;

}  // namespace

SessionEngine::SessionEngine(const SessionSettings& settings) : top_k_(settings.options.top_k) {
  const std::vector<std::string_view> names = CoreEngineNames(settings.engine);
  EngineOptions options = settings.options;
  if (names.size() > 1) options.top_k = std::max(options.top_k, kCombinedDepth);
  for (std::string_view name : names) engines_.push_back(CreateEngine(name, options));
}

FrameUpdate SessionEngine::Observe(const std::shared_ptr<const ViewIndexSnapshot>& index,
                                   const std::shared_ptr<const RejectionCalibration>& calibration,
                                   const QueryFrame& frame) {
  for (auto& engine : engines_) engine->SetCalibration(calibration);
  if (engines_.size() == 1) return engines_[0]->Observe(index, frame);

  // Both engines validate identically, so the first throws before either changes state.
  std::vector<FrameUpdate> updates;
  for (auto& engine : engines_) updates.push_back(engine->Observe(index, frame));

  std::unordered_map<ObjectId, double> sum;
  for (const FrameUpdate& u : updates) {
    for (const RankedObject& r : u.ranking) sum[r.object] += r.score;
  }
  FrameUpdate combined;
  combined.frame_index = updates[0].frame_index;
  combined.move = updates[0].move;
  for (const auto& [object, total] : sum) {
    combined.ranking.push_back({object, total / static_cast<double>(updates.size())});
  }
  std::sort(combined.ranking.begin(), combined.ranking.end(),
            [](const RankedObject& a, const RankedObject& b) {
              return a.score != b.score ? a.score > b.score : a.object < b.object;
            });
  if (static_cast<int>(combined.ranking.size()) > top_k_) combined.ranking.resize(top_k_);
  combined.decision = Decision::kUndecided;
  if (!combined.ranking.empty()) {
    for (const FrameUpdate& u : updates) {
      if (!u.ranking.empty() && u.ranking[0].object == combined.ranking[0].object) {
        combined.decision = u.decision;
        combined.unknown_statistic = u.unknown_statistic;
        combined.unknown_p_value = u.unknown_p_value;
        combined.confidence = u.confidence;
        combined.pose = u.pose;
        break;
      }
    }
  }
  return combined;
}

void SessionEngine::Reset() {
  for (auto& engine : engines_) engine->Reset();
}

ViewIndex::SnapshotPreparation PrepareForSessions(const SessionSettings& defaults) {
  const bool hmm = RunsHmm(defaults.engine);
  const int states = defaults.options.hmm_states;
  return [hmm, states](const ViewIndexSnapshot& next, const ViewIndexSnapshot& previous) {
    next.ChangeSince(previous);
    if (hmm) SectorSimilarityTable::Of(next, states);
  };
}

}  // namespace orbit::server
