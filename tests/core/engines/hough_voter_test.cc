#include "core/engines/hough_voter.h"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

TEST(HoughVoterTest, OrientationMismatchWrapsEveryDifference) {
  // dBeta = wrap(10 - 350) = 20, dAlpha = 100 - 80 = 20: a perfect fit across 0/360.
  EXPECT_NEAR(OrientationMismatch(10, 350, 100, 80), 0, 1e-15);
  // dBeta = -90, dAlpha = 0: 90 degrees.
  EXPECT_DOUBLE_EQ(OrientationMismatch(0, 90, 0, 0), 90 * kDegree);
  // dBeta = 170, dAlpha = -170: the difference 340 wraps to -20.
  EXPECT_DOUBLE_EQ(OrientationMismatch(170, 0, 0, 170), 20 * kDegree);
}

// Two frames at azimuths 10 and 40 (dAlpha = -30); two entries per list.
//   path (0,0): 0.5 + 0.6, dBeta = 100 - 130 = -30: mismatch 0                 -> 1.1
//   path (0,1): 0.5 + 0.8, dBeta = -150: |-150 + 30| = 120 degrees             -> 1.3 - w 2pi/3
//   path (1,0): 0.9 + 0.6, dBeta = 70: 100 degrees                             -> 1.5 - w 5pi/9
//   path (1,1): 0.9 + 0.8, dBeta = -50: 20 degrees                             -> 1.7 - w pi/9
const std::vector<std::vector<HoughEntry>> kEntries = {
    {{0, 100, 0.5}, {1, 200, 0.9}},
    {{2, 130, 0.6}, {3, 250, 0.8}},
};
const std::vector<std::optional<double>> kAzimuths = {10, 40};

TEST(HoughVoterTest, PathScoresMatchHandComputation) {
  const double w = 0.5;
  EXPECT_DOUBLE_EQ(HoughPathScore(kEntries, kAzimuths, std::vector<int>{0, 0}, w), 1.1);
  EXPECT_NEAR(HoughPathScore(kEntries, kAzimuths, std::vector<int>{0, 1}, w),
              1.3 - w * 2 * std::numbers::pi / 3, 1e-12);
  EXPECT_NEAR(HoughPathScore(kEntries, kAzimuths, std::vector<int>{1, 0}, w),
              1.5 - w * 5 * std::numbers::pi / 9, 1e-12);
  EXPECT_NEAR(HoughPathScore(kEntries, kAzimuths, std::vector<int>{1, 1}, w),
              1.7 - w * std::numbers::pi / 9, 1e-12);
}

TEST(HoughVoterTest, BestPathFollowsTheWeightOfTheOrientationTerm) {
  const HoughPath light = BestHoughPath(kEntries, kAzimuths, 0.5);
  EXPECT_EQ(light.choice, (std::vector<int>{1, 1}));
  EXPECT_NEAR(light.score, 1.7 - 0.5 * std::numbers::pi / 9, 1e-12);
  // w = 2: (1,1) drops to 1.7 - 0.698 = 1.002 < 1.1.
  const HoughPath heavy = BestHoughPath(kEntries, kAzimuths, 2.0);
  EXPECT_EQ(heavy.choice, (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(heavy.score, 1.1);
  // w = 0: the best similarity of each list.
  EXPECT_DOUBLE_EQ(BestHoughPath(kEntries, kAzimuths, 0).score, 1.7);
}

// The dynamic programme against enumeration of all N_L^n paths on random small cases.
TEST(HoughVoterTest, DynamicProgrammeEqualsBruteForceOnRandomCases) {
  std::mt19937 random(20240611);
  std::uniform_real_distribution<double> similarity(0, 1), angle(-400, 400), weight(0, 3);
  std::uniform_int_distribution<int> frames(1, 6), list(1, 4);
  for (int trial = 0; trial < 500; ++trial) {
    const int n = frames(random);
    std::vector<std::vector<HoughEntry>> entries(n);
    std::vector<std::optional<double>> azimuths(n);
    for (int k = 0; k < n; ++k) {
      // About one frame in five without an azimuth: its steps cost nothing (StepCost).
      azimuths[k] = similarity(random) < 0.2 ? std::nullopt : std::optional<double>(angle(random));
      const int size = list(random);
      for (int j = 0; j < size; ++j) entries[k].push_back({j, angle(random), similarity(random)});
    }
    const double w = weight(random);
    // Enumerate every path as a mixed-radix counter.
    double brute = -INFINITY;
    std::vector<int> choice(n, 0);
    while (true) {
      brute = std::max(brute, HoughPathScore(entries, azimuths, choice, w));
      int k = 0;
      while (k < n && ++choice[k] == static_cast<int>(entries[k].size())) choice[k++] = 0;
      if (k == n) break;
    }
    const HoughPath best = BestHoughPath(entries, azimuths, w);
    ASSERT_NEAR(best.score, brute, 1e-12) << "trial " << trial;
    ASSERT_NEAR(HoughPathScore(entries, azimuths, best.choice, w), best.score, 1e-12);
  }
}

TEST(HoughVoterTest, BestPathRejectsMalformedInput) {
  EXPECT_THROW(BestHoughPath({}, {}, 0.5), std::invalid_argument);
  const std::vector<std::vector<HoughEntry>> hole = {{{0, 0, 1}}, {}};
  EXPECT_THROW(BestHoughPath(hole, std::vector<std::optional<double>>{0, 0}, 0.5),
               std::invalid_argument);
  EXPECT_THROW(BestHoughPath(kEntries, std::vector<std::optional<double>>{0}, 0.5),
               std::invalid_argument);
}

}  // namespace
}  // namespace orbit
