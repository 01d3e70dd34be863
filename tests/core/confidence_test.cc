// Confidence: the logistic of core/confidence.h, checked at hand-computed points.
#include "core/confidence.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(ConfidenceTest, FollowsTheFittedLogistic) {
  // U = 0 (frames equal to the winner's views): 1 / (1 + e^-10.18) = 0.999962.
  EXPECT_NEAR(Confidence(0), 0.999962, 1e-6);
  // The midpoint U = 10.18 / 8.35 = 1.2192 gives 0.5.
  EXPECT_NEAR(Confidence(10.18 / 8.35), 0.5, 1e-12);
  // U = 2 (far from the winner): 1 / (1 + e^6.52) = 0.001472.
  EXPECT_NEAR(Confidence(2), 0.001472, 1e-6);
}

TEST(ConfidenceTest, FallsAsTheFramesLookLessKnown) {
  double previous = 1;
  for (double u = 0; u <= 3; u += 0.1) {
    const double c = Confidence(u);
    EXPECT_LT(c, previous);
    EXPECT_GE(c, 0);
    previous = c;
  }
}

TEST(ConfidenceTest, IsZeroForANonFiniteStatistic) {
  EXPECT_EQ(Confidence(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(Confidence(std::numeric_limits<double>::infinity()), 0);
}

}  // namespace
}  // namespace orbit
