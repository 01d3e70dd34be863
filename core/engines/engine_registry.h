// The engines, by name: the one list of them (docs/design.md#engines). The server's sessions,
// `orbit eval --methods`, the API's Engine values (api/engines/engine_names.h, whose test checks
// that the two agree) and every --help read their names here.
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "core/engines/recognition_engine.h"

namespace orbit {

struct EngineKind {
  std::string_view name;     // "vci"
  std::string_view summary;  // one line, for --help and reports
  // Whether it keeps an orientation HMM, whose memory grows with window x hmm_states per
  // object (the server bounds that product).
  bool keeps_hmm = false;
  // A new session of this engine. Throws std::invalid_argument for options out of range.
  std::unique_ptr<RecognitionEngine> (*create)(const EngineOptions& options) = nullptr;
};

// {"eis", "siis", "eiis", "vci-bm", "vci-w0", "vci", "hmm", "vci-hmm"}, in this order.
std::span<const EngineKind> EngineKinds();
std::span<const std::string_view> EngineNames();

// The engine called `name`; throws std::invalid_argument listing the names otherwise.
const EngineKind& FindEngine(std::string_view name);

// A new session of the engine called `name`.
// Throws std::invalid_argument for an unknown name or options out of range.
std::unique_ptr<RecognitionEngine> CreateEngine(std::string_view name,
                                                const EngineOptions& options = {});

// What the first frame of every session of engine `name` with `options` would compute on
// `snapshot` and can share (the HMM's sector table: SectorSimilarityTable::Of), computed now.
// Thread-safe; cheap when already done.
void PrepareSnapshot(std::string_view name, const EngineOptions& options,
                     const ViewIndexSnapshot& snapshot);

}  // namespace orbit
