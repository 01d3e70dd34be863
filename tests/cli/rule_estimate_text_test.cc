// RuleEstimateText: what `orbit info` and `orbit enroll` say of the accept / unknown rule, word
// for word.
#include "cli/rule_estimate_text.h"

#include <gtest/gtest.h>

namespace orbit::cli {
namespace {

v1::RuleEstimate Estimate(int objects, double known, double unknown, bool held) {
  v1::RuleEstimate estimate;
  estimate.set_objects(objects);
  estimate.set_frames(8);
  estimate.set_known_accepted(known);
  estimate.set_unknown_accepted(unknown);
  estimate.set_held_by_known_ceiling(held);
  return estimate;
}

TEST(RuleEstimateTextTest, NotCalibratedSaysWhatItNeeds) {
  EXPECT_EQ(RuleEstimateText(v1::RuleEstimate(), 1, 0.17),
            "accept / unknown  not calibrated: it needs two objects enrolled; until then every "
            "answer is undecided\n");
}

TEST(RuleEstimateTextTest, FewObjectsWarnAndAHeldThresholdIsNamed) {
  EXPECT_EQ(RuleEstimateText(Estimate(5, 0.994, 0.041, true), 5, 0.17),
            "accept / unknown  calibrated on 5 objects: of windows of 8 frames, accepts about "
            "99% of the enrolled objects' own and 4% of objects left out (target 17%); the "
            "threshold is held at what the enrolled objects' own views need\n"
            "  few objects: on objects nobody enrolled the rate can stray far from this "
            "estimate (docs/results/recognition.md, \"Small catalogues\"); enroll more objects "
            "to steady it\n");
}

TEST(RuleEstimateTextTest, ManyObjectsAtTheTargetAndARecalibrationUnderWay) {
  EXPECT_EQ(RuleEstimateText(Estimate(kFewCalibrationObjects, 0.97, 0.17, false), 21, 0.17),
            "accept / unknown  calibrated on 20 objects (recalibrating for the 21 held now): of "
            "windows of 8 frames, accepts about 97% of the enrolled objects' own and 17% of "
            "objects left out (target 17%)\n");
}

TEST(RuleEstimateTextTest, KnownWindowsOftenRejectedSayHowToEnroll) {
  EXPECT_EQ(RuleEstimateText(Estimate(30, 0.65, 0.12, false), 30, 0.17),
            "accept / unknown  calibrated on 30 objects: of windows of 8 frames, accepts about "
            "65% of the enrolled objects' own and 12% of objects left out (target 17%)\n"
            "  an enrolled object is often answered unknown between its views: enroll a view "
            "every 15-25 degrees, on the background and in the light it will be seen in\n");
}

}  // namespace
}  // namespace orbit::cli
