#include "core/engines/engine_registry.h"

#include <array>
#include <stdexcept>
#include <string>

#include "core/engines/baseline_engines.h"
#include "core/engines/combined_engine.h"
#include "core/engines/hough_voter.h"
#include "core/engines/orientation_hmm.h"
#include "core/engines/sector_similarity_table.h"

namespace orbit {
namespace {

constexpr std::array<EngineKind, 8> kEngines = {{
    {"eis", "EIS: each frame's nearest view, averaged (baseline)", false,
     [](const EngineOptions& o) { return MakeBaselineEngine(BaselineMethod::kEis, o); }},
    {"siis", "SIIS: one frame searched, the others matched through the turns (baseline)", false,
     [](const EngineOptions& o) { return MakeBaselineEngine(BaselineMethod::kSiis, o); }},
    {"eiis", "EIIS: every rotation of the object tried through the turns (baseline)", false,
     [](const EngineOptions& o) { return MakeBaselineEngine(BaselineMethod::kEiis, o); }},
    {"vci-bm", "VCI best match: Hough votes over retrieval lists, no extension, w = 0", false,
     [](const EngineOptions& o) { return MakeHoughEngine(HoughVariant::kBestMatch, o); }},
    {"vci-w0", "VCI_W: lists extended by the most similar view, w = 0", false,
     [](const EngineOptions& o) { return MakeHoughEngine(HoughVariant::kWeightless, o); }},
    {"vci", "VCI: lists extended by the turns, orientation term w", false,
     [](const EngineOptions& o) { return MakeHoughEngine(HoughVariant::kOriented, o); }},
    {"hmm", "the orientation HMM over azimuth sectors, decoded by Viterbi", true, MakeHmmEngine},
    {"vci-hmm", "vci and hmm side by side, their scores averaged", true, MakeVciHmmEngine},
}};

constexpr std::array<std::string_view, kEngines.size()> kNames = [] {
  std::array<std::string_view, kEngines.size()> names{};
  for (std::size_t i = 0; i < kEngines.size(); ++i) names[i] = kEngines[i].name;
  return names;
}();

}  // namespace

std::span<const EngineKind> EngineKinds() { return kEngines; }

std::span<const std::string_view> EngineNames() { return kNames; }

const EngineKind& FindEngine(std::string_view name) {
  for (const EngineKind& kind : kEngines) {
    if (kind.name == name) return kind;
  }
  std::string known;
  for (const std::string_view n : kNames) known += (known.empty() ? "" : ", ") + std::string(n);
  throw std::invalid_argument("unknown engine \"" + std::string(name) + "\" (known: " + known +
                              ")");
}

std::unique_ptr<RecognitionEngine> CreateEngine(std::string_view name,
                                                const EngineOptions& options) {
  return FindEngine(name).create(options);
}

void PrepareSnapshot(std::string_view name, const EngineOptions& options,
                     const ViewIndexSnapshot& snapshot) {
  if (FindEngine(name).keeps_hmm) SectorSimilarityTable::Of(snapshot, options.hmm_states);
}

}  // namespace orbit
