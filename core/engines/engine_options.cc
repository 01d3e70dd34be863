#include "core/engines/engine_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace orbit {
namespace {

// Throws "<prefix><field> must be in <range>, got <value>" unless `in_range`.
template <typename T>
void Require(bool in_range, std::string_view prefix, std::string_view field, std::string_view range,
             T value) {
  if (in_range) return;
  std::ostringstream message;
  message << prefix << field << " must be in " << range << ", got " << value;
  throw std::invalid_argument(message.str());
}

std::string Closed(double low, double high) {
  std::ostringstream text;
  text << '[' << low << ", " << high << ']';
  return text.str();
}

std::string Integers(int low, int high) {
  return std::to_string(low) + ".." + std::to_string(high);
}

}  // namespace

void ValidateEngineOptions(const EngineOptions& o, std::string_view p) {
  // Every comparison is written so that NaN fails it.
  Require(o.window >= 1 && o.window <= kMaxWindow, p, "window", Integers(1, kMaxWindow), o.window);
  Require(o.list_length >= 1 && o.list_length <= kMaxListLength, p, "list_length",
          Integers(1, kMaxListLength), o.list_length);
  Require(o.orientation_weight >= 0 && o.orientation_weight <= kMaxOrientationWeight, p,
          "orientation_weight", Closed(0, kMaxOrientationWeight), o.orientation_weight);
  Require(o.hmm_states >= 1 && o.hmm_states <= kMaxHmmStates, p, "hmm_states",
          Integers(1, kMaxHmmStates), o.hmm_states);
  Require(o.hmm_sharpness >= 0 && o.hmm_sharpness <= kMaxHmmSharpness, p, "hmm_sharpness",
          Integers(0, kMaxHmmSharpness), o.hmm_sharpness);
  Require(std::isfinite(o.threshold) && o.threshold > 0, p, "threshold", "(0, inf)", o.threshold);
  Require(o.false_accept_rate > 0 && o.false_accept_rate < 1, p, "false_accept_rate", "(0, 1)",
          o.false_accept_rate);
  Require(o.known_accept_rate >= 0 && o.known_accept_rate < 1, p, "known_accept_rate", "[0, 1)",
          o.known_accept_rate);
  Require(o.top_k >= 1 && o.top_k <= kMaxTopK, p, "top_k", Integers(1, kMaxTopK), o.top_k);
  Require(o.nearest_view_weight >= 0 && o.nearest_view_weight <= 1, p, "nearest_view_weight",
          Closed(0, 1), o.nearest_view_weight);
  Require(o.averaged_views >= 2 && o.averaged_views <= kMaxAveragedViews, p, "averaged_views",
          Integers(2, kMaxAveragedViews), o.averaged_views);
  Require(std::isfinite(o.ambiguity_margin) && o.ambiguity_margin >= 0, p, "ambiguity_margin",
          "[0, inf)", o.ambiguity_margin);
  Require(o.candidate_objects >= 0 && o.candidate_objects <= kMaxCandidateObjects, p,
          "candidate_objects", Integers(0, kMaxCandidateObjects), o.candidate_objects);
  Require(o.candidates_above >= 0 && o.candidates_above <= kMaxCandidatesAbove, p,
          "candidates_above", Integers(0, kMaxCandidatesAbove), o.candidates_above);
}

int RankedDepth(const EngineOptions& options) {
  return options.nearest_view_weight > 0 ? std::max(options.top_k, kNearestViewCandidates)
                                         : options.top_k;
}

}  // namespace orbit
