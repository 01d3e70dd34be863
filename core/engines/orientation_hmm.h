// The orientation HMM (docs/design.md#orientation-hmm; the thesis' part 3): each object is a
// hidden Markov model whose states are N equal azimuth sectors; the orientation sensor's
// measured change between frames sets the transition probabilities.
//
//   states        S_i = sector i of the object's model azimuths, [i*360/N, (i+1)*360/N); its
//                 descriptor is the mean CEDD of the model views in it (IndexedObject::Sectors).
//   initial       pi_i = width(S_i) / 360.
//   transitions   for consecutive frames with measured change Delta = alpha(o_t) - alpha(o_{t-1})
//                 (wrapped to (-180, 180]): a_ij = |L_j intersect R_i| / |L_j|, where R_i is
//                 sector i and L_j is sector j shifted by -Delta (circular arcs): the share of
//                 the azimuths that land in sector j after turning by Delta which started in
//                 sector i. Columns sum to 1; rows too when the sectors are equal.
//   emissions     b_i(o) = TC(S_i, o) / sum_j TC(S_j, o) (uniform when every TC is 0).
//   decoding      Viterbi per object over the window (emissions floored at 1e-12 so that a zero
//                 similarity never makes every path impossible). The engine runs it in linear
//                 space with per-frame rescaling and TC_i in place of b_i: b_i(o_t) differs from
//                 TC_i by a factor common to all states at frame t, so every path's rank, and
//                 so the decoded path, is the same.
//   winner        argmax_k mean_t TC(o_t, state on object k's Viterbi path at t); this mean is
//                 the reported score.
// Matched views (rejection rule): at each frame, the model view of the path's sector most
// similar to the frame.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "core/base/angles.h"
#include "core/engines/batch_viterbi.h"
#include "core/engines/recognition_engine.h"

namespace orbit {

// N equal sectors: sector s = [s * 360/N, (s+1) * 360/N). Throws std::invalid_argument when
// count < 1.
std::vector<Arc> EqualSectors(int count);

// pi_i = width(S_i) / 360.
std::vector<double> InitialProbabilities(std::span<const Arc> sectors);

// a[i][j] as above, for measured change `delta` (degrees, any finite value).
// Throws std::invalid_argument when a sector is empty or invalid (ArcOverlap's rules).
std::vector<std::vector<double>> TransitionMatrix(std::span<const Arc> sectors, double delta);

// The same transitions kept sparse, for BatchViterbi: into(j) lists (i, a_ij) for a_ij > 0.
SparseTransitions MakeSparseTransitions(std::span<const Arc> sectors, double delta);
// The same, into `step`'s buffers (an HMM session reuses a departed frame's).
void MakeSparseTransitions(std::span<const Arc> sectors, double delta, SparseTransitions& step);

// The transitions when the turn between two frames is not known (a frame without azimuth):
// from any sector to sector j with its initial probability, a_ij = pi_j, so the path may jump
// anywhere and only the emissions choose it.
SparseTransitions UnknownTurnTransitions(std::span<const Arc> sectors);

// b_i = similarity_i / sum_j similarity_j; uniform when the sum is 0.
std::vector<double> Emissions(std::span<const double> state_similarities);

struct ViterbiPath {
  std::vector<int> states;     // most probable state per frame
  double log_probability = 0;  // its log probability (-inf when every path is impossible)
};

// Most probable state sequence. transitions[t-1] leads from frame t-1 to frame t;
// emissions[t][i] = b_i(o_t). Ties: the lower state index.
// Throws std::invalid_argument when emissions is empty or the sizes disagree.
ViterbiPath Viterbi(std::span<const double> initial,
                    std::span<const std::vector<std::vector<double>>> transitions,
                    std::span<const std::vector<double>> emissions);

// Throws std::invalid_argument when options are out of range.
std::unique_ptr<RecognitionEngine> MakeHmmEngine(const EngineOptions& options);

}  // namespace orbit
