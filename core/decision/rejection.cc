#include "core/decision/rejection.h"

#include <cmath>
#include <stdexcept>
#include <string>

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

std::string_view DecisionName(Decision decision) {
  switch (decision) {
    case Decision::kAccept: return "ACCEPT";
    case Decision::kUnknown: return "UNKNOWN";
    case Decision::kUndecided: break;
  }
  return "UNDECIDED";
}

std::string_view RejectionRuleName(RejectionRule rule) {
  return rule == RejectionRule::kCalibrated ? "calibrated" : "th";
}

RejectionRule ParseRejectionRule(std::string_view name) {
  for (const RejectionRule rule : {RejectionRule::kTypicalDistance, RejectionRule::kCalibrated}) {
    if (name == RejectionRuleName(rule)) return rule;
  }
  throw std::invalid_argument("unknown rejection rule \"" + std::string(name) +
                              "\" (known: th, calibrated)");
}

}  // namespace orbit
