// Confidence: the logistic of core/decision/confidence.h, checked at hand-computed points.
#include "core/decision/confidence.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(ConfidenceTest, FollowsTheFittedLogistic) {
  // One frame: z = 8.375 - 6.894 U.  U = 0: 0.999769; U = 1: z = 1.481, 0.814724;
  // U = 2: z = -5.413, 0.004438.
  EXPECT_NEAR(Confidence(0, 1), 0.999769, 1e-6);
  EXPECT_NEAR(Confidence(1, 1), 0.814724, 1e-6);
  EXPECT_NEAR(Confidence(2, 1), 0.004438, 1e-6);
  // Eight frames (ln 8 = 2.0794): U = 1: z = 8.375 - 6.894 + 8.4072 - 6.9141 = 2.9741, 0.951387;
  // U = 1.5: z = -3.9293, 0.019265.
  EXPECT_NEAR(Confidence(1, 8), 0.951387, 1e-5);
  EXPECT_NEAR(Confidence(1.5, 8), 0.019265, 1e-5);
}

TEST(ConfidenceTest, FallsAsTheFramesLookLessKnown) {
  for (const int frames : {1, 4, 8, 16}) {
    double previous = 1;
    for (double u = 0; u <= 3; u += 0.1) {
      const double c = Confidence(u, frames);
      EXPECT_LT(c, previous) << "U " << u << ", " << frames << " frames";
      EXPECT_GE(c, 0);
      previous = c;
    }
  }
}

TEST(ConfidenceTest, IsZeroForANonFiniteStatistic) {
  EXPECT_EQ(Confidence(std::numeric_limits<double>::quiet_NaN(), 1), 0);
  EXPECT_EQ(Confidence(std::numeric_limits<double>::infinity(), 8), 0);
}

}  // namespace
}  // namespace orbit
