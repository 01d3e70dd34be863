// The baseline engines of the thesis (docs/design.md#engines), against which VCI and the HMM are
// measured. Each keeps, per window frame, the Tanimoto coefficient of the frame with every view
// of the index (one brute-force pass per frame, ViewIndexSnapshot::SimilarityToEveryView), so
// they always search exactly whatever the index's mode.
//
// With frames q_1..q_n in the window, T = 1 - TC, and alpha the device azimuths:
//   EIS   T_EIS(c_i) = (1/n) sum_k min_f T(q_k, c_{i,f}).
//   SIIS  the selected frame is the window's oldest, q_1. Its best view f* of c_i is found by
//         search; every other frame k is compared with the views of c_i on either side of
//         alpha(c_{i,f*}) + (alpha(q_k) - alpha(q_1)) (the same relative orientation; nearest
//         available view on the left and on the right, the better of the two counts).
//         T_SIIS(c_i) = mean over frames of those distances.
//   EIIS  as SIIS, but the anchor view of q_1 is every view f of c_i in turn (every rotation of
//         the candidate a view allows) rather than the best one; T_EIIS(c_i) = min over f of
//         the mean distance.
// Score reported: 1 - T (higher is better). Matched views: the view each frame was compared
// with. Every object of the index is ranked.
#pragma once

#include <memory>

#include "core/engines/recognition_engine.h"

namespace orbit {

enum class BaselineMethod { kEis, kSiis, kEiis };

// Throws std::invalid_argument when options are out of range.
std::unique_ptr<RecognitionEngine> MakeBaselineEngine(BaselineMethod method,
                                                      const EngineOptions& options);

}  // namespace orbit
