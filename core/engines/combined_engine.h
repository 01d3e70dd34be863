// The engine "vci-hmm": VCI and the orientation HMM run side by side on every frame, objects
// ranked by the mean of their two scores (docs/design.md#vci-and-hmm-together).
//
// An object missing from one engine's ranking counts 0 there; both rankings are taken
// kCombinedDepth deep so that this is rare. The decision, unknown statistic, confidence and pose
// are those of whichever engine ranks the combined winner first (VCI's when both do), undecided
// when neither does; the move, frame index and readings are VCI's.
#pragma once

#include <memory>

#include "core/engines/recognition_engine.h"

namespace orbit {

// How deep each engine ranks when two are combined.
inline constexpr int kCombinedDepth = 32;

// Throws std::invalid_argument for options out of range.
std::unique_ptr<RecognitionEngine> MakeVciHmmEngine(const EngineOptions& options);

}  // namespace orbit
