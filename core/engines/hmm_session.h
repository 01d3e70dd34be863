// HmmSession: what the orientation HMM's two engines share (docs/design.md#orientation-hmm): the
// states and their transitions from frame to frame, the decoding of a few objects' kept emissions
// over the window, and the matched views along a decoded path. The engine that scores every
// object (core/engines/orientation_hmm.cc) and the one that scores candidates
// (core/engines/candidate_hmm.cc) differ only in which objects they keep emissions for.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "core/base/angles.h"
#include "core/engines/batch_viterbi.h"
#include "core/engines/windowed_engine.h"

namespace orbit {

class HmmSession : public WindowedEngine {
 protected:
  // Throws std::invalid_argument when `options` are out of range.
  explicit HmmSession(const EngineOptions& options);

  // The transitions from the last frame stepped to into `frame`, into `step` (its buffers
  // reused): the measured turn's, or any-state-to-any when either frame lacks an azimuth; left
  // as it is for the first frame. Remembers `frame` for the next step.
  void StepTo(const QueryFrame& frame, SparseTransitions& step);
  // Forgets the last frame (the next is a first).
  void ForgetSteps() { previous_.reset(); }

  // Decodes `lanes` objects over the window's `frames` frames: kept[t * lanes + j] points to
  // object j's states_ emissions at frame t as the window keeps them (EmissionsFromSimilarities,
  // unsharpened); steps[t - 1] leads into frame t. They are gathered into BatchViterbi's
  // [state][lane] layout and sharpened as they are copied. Sets sums[j] to the sum over frames of
  // the similarity of object j's path (0 where unseen); the paths stay for CompletePath.
  void DecodeKept(std::span<const float* const> kept, std::size_t frames, std::size_t lanes,
                  std::span<const SparseTransitions* const> steps, std::vector<double>& sums);

  // Fills `assessment`'s matched views and latest azimuth from the path of `lane` in the last
  // DecodeKept: at each frame, the view of the path's sector most similar to the frame.
  void CompletePath(std::size_t lane, std::span<const QueryFrame> window, const ObjectRows& rows,
                    Assessment& assessment) const;

  const int states_;
  const std::vector<Arc> sectors_;

 private:
  const SparseTransitions unknown_turn_;  // the step to or from a frame without azimuth
  BatchViterbi viterbi_;                  // holds the last decoding's paths
  std::optional<QueryFrame> previous_;    // the last frame stepped to
};

}  // namespace orbit
