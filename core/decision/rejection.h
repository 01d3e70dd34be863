// The accept / unknown decision (docs/design.md#threshold-rule): the best object is accepted
// when the query frames fit the views matched to them about as well as those views fit distorted
// copies of themselves.
//
//   T_M = mean over frames of T(q_k, matched view)      (T = 1 - TC)
//   accept  iff  T_M / mean(Ttyp of the matched views) <= Th        (Th default 2)
//
// Pure and thread-safe.
#pragma once

#include <span>
#include <string_view>

namespace orbit {

enum class Decision {
  kAccept,     // the best object fits as well as its views fit distorted copies of themselves
  kUnknown,    // the best object fits too badly: an object the index does not know
  kUndecided,  // no answer possible: empty index, or the matched views have no typical distance
};

std::string_view DecisionName(Decision decision);  // "ACCEPT", "UNKNOWN", "UNDECIDED"

enum class RejectionRule {
  kTypicalDistance,  // "th": the thesis' rule (docs/design.md#threshold-rule)
  kCalibrated,       // "calibrated": the product's (docs/design.md#calibrated-rule)
};

// "th", "calibrated".
std::string_view RejectionRuleName(RejectionRule rule);
// The rule called `name`; throws std::invalid_argument naming the known ones otherwise.
RejectionRule ParseRejectionRule(std::string_view name);

// One query frame and the model view matched to it.
struct MatchedDistance {
  double distance = 0;          // T(q_k, view), in [0, 1]
  double typical_distance = 0;  // Ttyp(view); 0 when unknown
};

// kAccept or kUnknown by the rule above; kUndecided when `matches` is empty or the mean typical
// distance is not positive (the model was enrolled without typical distances, so the ratio has
// no meaning).
// Throws std::invalid_argument when threshold is not positive and finite.
Decision DecideRecognition(std::span<const MatchedDistance> matches, double threshold);

}  // namespace orbit
