#include "core/engines/hmm_session.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/base/cpu_dispatch.h"
#include "core/engines/hmm_emissions.h"
#include "core/engines/orientation_hmm.h"
#include "core/index/indexed_object.h"
#include "core/index/similarity_rows.h"

namespace orbit {

HmmSession::HmmSession(const EngineOptions& options)
    : WindowedEngine("hmm", options),
      states_(options.hmm_states),
      sectors_(EqualSectors(states_)),
      unknown_turn_(UnknownTurnTransitions(sectors_)),
      viterbi_(InitialProbabilities(sectors_)) {}

void HmmSession::StepTo(const QueryFrame& frame, SparseTransitions& step) {
  if (previous_) {
    const std::optional<double> turn = MeasuredTurn(*previous_, frame);
    if (turn) {
      MakeSparseTransitions(sectors_, *turn, step);  // in the reused frame's buffers
    } else {
      step = unknown_turn_;
    }
  }
  previous_ = frame;
}

void HmmSession::DecodeKept(std::span<const float* const> kept, std::size_t frames,
                            std::size_t lanes, std::span<const SparseTransitions* const> steps,
                            std::vector<double>& sums) {
  // The scratch is the thread's: warm in its cache whichever session it serves.
  const std::size_t states = static_cast<std::size_t>(states_);
  thread_local std::vector<float> gathered;  // [frame][state][lane]
  gathered.resize(frames * states * lanes);
  std::vector<const float*> emissions;
  for (std::size_t t = 0; t < frames; ++t) {
    float* lanes_of_frame = &gathered[t * states * lanes];
    for (std::size_t j = 0; j < lanes; ++j) {
      const float* object_states = kept[t * lanes + j];
      for (std::size_t i = 0; i < states; ++i) {
        lanes_of_frame[i * lanes + j] = std::abs(object_states[i]);  // kUnseenEmission: 1
      }
    }
    RunHotLoop<Sharpen>(lanes_of_frame, states * lanes, options().hmm_sharpness);
    emissions.push_back(lanes_of_frame);
  }
  viterbi_.Decode(emissions, steps, lanes);
  sums.assign(lanes, 0.0);
  for (std::size_t j = 0; j < lanes; ++j) {
    const std::span<const std::uint16_t> path = viterbi_.path(j);
    for (std::size_t t = 0; t < frames; ++t) {
      // The TC of the path's state, from the kept (unsharpened) emissions; 0 when unseen.
      sums[j] += std::max(kept[t * lanes + j][path[t]], 0.0f);
    }
  }
}

void HmmSession::CompletePath(std::size_t lane, std::span<const QueryFrame> window,
                              const ObjectRows& rows, Assessment& assessment) const {
  const std::span<const std::uint16_t> path = viterbi_.path(lane);
  const SectorViews& sectors = assessment.object->Sectors(states_);
  const auto& views = assessment.object->model().views;
  assessment.matched.clear();
  for (std::size_t t = 0; t < window.size(); ++t) {
    MatchedView best{static_cast<int>(t), -1, -1};
    for (const int v : sectors.views[path[t]]) {
      const double tc = rows.rows[t][v];
      if (tc > best.similarity) best = {static_cast<int>(t), v, tc};
    }
    assessment.matched.push_back(best);
  }
  assessment.latest_azimuth = views[assessment.matched.back().view].azimuth;
}

}  // namespace orbit
