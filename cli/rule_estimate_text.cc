#include "cli/rule_estimate_text.h"

#include <cmath>
#include <sstream>

namespace orbit::cli {
namespace {

std::string Percent(double share) {
  std::ostringstream text;
  text << std::lround(100 * share) << "%";
  return text.str();
}

}  // namespace

std::string RuleEstimateText(const v1::RuleEstimate& estimate, std::int64_t server_objects,
                             double target) {
  std::ostringstream text;
  text << "accept / unknown  ";
  if (estimate.objects() == 0) {
    text << "not calibrated: it needs two objects enrolled; until then every answer is "
            "undecided\n";
    return text.str();
  }
  text << "calibrated on " << estimate.objects() << " objects";
  if (server_objects != estimate.objects()) {
    text << " (recalibrating for the " << server_objects << " held now)";
  }
  text << ": of windows of " << estimate.frames() << " frames, accepts about "
       << Percent(estimate.known_accepted()) << " of the enrolled objects' own and "
       << Percent(estimate.unknown_accepted()) << " of objects left out (target " << Percent(target)
       << ")";
  if (estimate.held_by_known_ceiling()) {
    text << "; the threshold is held at what the enrolled objects' own views need";
  }
  text << "\n";
  if (estimate.known_accepted() < kFewKnownAccepted) {
    text << "  an enrolled object is often answered unknown between its views: enroll a view "
            "every 15-25 degrees, on the background and in the light it will be seen in\n";
  }
  if (estimate.objects() < kFewCalibrationObjects) {
    text << "  few objects: on objects nobody enrolled the rate can stray far from this "
            "estimate (docs/results/recognition.md, \"Small catalogues\"); enroll more objects "
            "to steady it\n";
  }
  return text.str();
}

}  // namespace orbit::cli
