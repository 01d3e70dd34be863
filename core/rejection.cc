#include "core/rejection.h"

#include <cmath>
#include <stdexcept>

namespace orbit {

Decision DecideRecognition(std::span<const MatchedDistance> matches, double threshold) {
  if (!std::isfinite(threshold) || threshold <= 0) {
    throw std::invalid_argument("recognition threshold must be positive and finite");
  }
  if (matches.empty()) return Decision::kUndecided;
  double distance_sum = 0, typical_sum = 0;
  for (const MatchedDistance& match : matches) {
    distance_sum += match.distance;
    typical_sum += match.typical_distance;
  }
  if (!(typical_sum > 0)) return Decision::kUndecided;
  // T_M / mean(Ttyp) with the common 1/n cancelled.
  return distance_sum / typical_sum <= threshold ? Decision::kAccept : Decision::kUnknown;
}

}  // namespace orbit
