#include "core/decision/rejection.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(RejectionTest, AcceptsUpToThresholdTimesTheTypicalDistance) {
  // T_M = (0.1 + 0.3) / 2 = 0.2; mean Ttyp = (0.05 + 0.15) / 2 = 0.1: ratio 2.
  const std::vector<MatchedDistance> at_threshold = {{0.1, 0.05}, {0.3, 0.15}};
  EXPECT_EQ(DecideRecognition(at_threshold, 2.0), Decision::kAccept);
  EXPECT_EQ(DecideRecognition(at_threshold, 1.99), Decision::kUnknown);
  // T_M = 0.21, mean Ttyp = 0.1: ratio 2.1.
  const std::vector<MatchedDistance> beyond = {{0.1, 0.1}, {0.32, 0.1}};
  EXPECT_EQ(DecideRecognition(beyond, 2.0), Decision::kUnknown);
  EXPECT_EQ(DecideRecognition(beyond, 2.2), Decision::kAccept);
}

TEST(RejectionTest, UndecidedWithoutMatchesOrTypicalDistances) {
  EXPECT_EQ(DecideRecognition({}, 2.0), Decision::kUndecided);
  const std::vector<MatchedDistance> unknown_typical = {{0.1, 0}, {0.2, 0}};
  EXPECT_EQ(DecideRecognition(unknown_typical, 2.0), Decision::kUndecided);
}

TEST(RejectionTest, RejectsBadThresholds) {
  const std::vector<MatchedDistance> one = {{0.1, 0.1}};
  EXPECT_THROW(DecideRecognition(one, 0), std::invalid_argument);
  EXPECT_THROW(DecideRecognition(one, -1), std::invalid_argument);
  EXPECT_THROW(DecideRecognition(one, NAN), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
