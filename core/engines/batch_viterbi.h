// BatchViterbi: the most probable state path of many HMMs at once, one per object, that share
// their states' layout, initial probabilities and transitions and differ only in emissions
// (docs/design.md#orientation-hmm: the transitions come from the measured orientation change,
// the same for every object). Objects sit in SIMD lanes, so a frame step costs a few vector
// operations per non-zero transition, whatever the number of objects.
//
// It decodes what Viterbi() (orientation_hmm.h) decodes, in linear space with floats: after
// every frame each object's scores are rescaled to a maximum of 1, which changes no path's rank.
// One difference: a path more than 1/FLT_MIN (about 1e38) times less probable than its object's
// best at some frame is dropped (set to 0, as float underflow would, but without the slow
// subnormal range). Ties go to the lower state index, as in Viterbi().
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace orbit {

// One frame step's transitions, sparse: into(j) lists (i, a_ij) for every a_ij > 0, i
// ascending. Kept in two flat arrays (a window holds one step per frame, read on every answer).
struct SparseTransitions {
  std::vector<std::uint32_t> first;  // [states + 1]: into(j) is entries[first[j], first[j + 1])
  std::vector<std::pair<int, float>> entries;

  std::size_t states() const { return first.empty() ? 0 : first.size() - 1; }
  std::span<const std::pair<int, float>> into(std::size_t j) const {
    return {entries.data() + first[j], first[j + 1] - first[j]};
  }
};

class BatchViterbi {
 public:
  // `initial` = pi_i per state (InitialProbabilities). Throws std::invalid_argument when it is
  // empty or has more than 65536 states.
  explicit BatchViterbi(std::vector<double> initial);

  // Decodes `objects` HMMs over frames 0..F-1. emissions[t] points to b(o_t) up to a factor
  // common to the frame, laid out [state * objects + object]; steps[t - 1] leads from frame
  // t - 1 to t (so steps.size() == emissions.size() - 1). On return, path(o)[t] is object o's
  // state at frame t. Throws std::invalid_argument when the sizes disagree.
  void Decode(std::span<const float* const> emissions,
              std::span<const SparseTransitions* const> steps, std::size_t objects);

  // Object o's decoded states, one per frame, valid until the next Decode.
  std::span<const std::uint16_t> path(std::size_t o) const {
    return {&paths_[o * frames_], frames_};
  }

 private:
  std::vector<float> initial_;
  std::size_t frames_ = 0;
  std::vector<std::uint16_t> paths_;  // [object][frame]
};

}  // namespace orbit
