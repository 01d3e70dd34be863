#include "evaluation/evaluation_protocol.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/base/angles.h"
#include "core/descriptor/distortion.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;

std::vector<double> Coil100Azimuths() {
  std::vector<double> azimuths;
  for (int a = 0; a < 360; a += 5) azimuths.push_back(a);
  return azimuths;
}

TEST(SampleTrialTest, RemovesExactlyTheViewsWithinTenDegreesOfAQueryView) {
  // Views at 0, 10, 21 and 355 degrees; one query view. By hand:
  //   query 0   -> 0, 10 (10 away, inclusive) and 355 (5 away across 0/360); 21 is 21 away
  //   query 10  -> 0, 10; 21 is 11 away, 355 is 15 away
  //   query 21  -> 21 only
  //   query 355 -> 0 (5 away) and 355; 10 is 15 away
  const std::vector<double> azimuths{0, 10, 21, 355};
  const std::map<int, std::vector<int>> expected{
      {0, {0, 1, 3}}, {1, {0, 1}}, {2, {2}}, {3, {0, 3}}};
  std::set<int> seen;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const TrialQuery query = SampleTrial(azimuths, 1, seed);
    ASSERT_EQ(query.views.size(), 1u);
    seen.insert(query.views[0]);
    EXPECT_EQ(query.removed_views, expected.at(query.views[0])) << "query view " << query.views[0];
  }
  EXPECT_EQ(seen.size(), 4u);  // every view was drawn at least once in 200 trials
}

TEST(SampleTrialTest, DrawsDistinctViewsInAzimuthOrder) {
  const std::vector<double> azimuths = Coil100Azimuths();
  for (int n : {1, 2, 4, 6, 8, 72}) {
    for (int trial = 0; trial < 20; ++trial) {
      const TrialQuery query = SampleTrial(azimuths, n, TrialSeed(1, 3, n, trial));
      ASSERT_EQ(query.views.size(), static_cast<std::size_t>(n));
      ASSERT_EQ(query.azimuths.size(), static_cast<std::size_t>(n));
      EXPECT_TRUE(std::is_sorted(query.views.begin(), query.views.end()));  // azimuth = 5 * index
      EXPECT_EQ(std::set<int>(query.views.begin(), query.views.end()).size(),
                static_cast<std::size_t>(n));
      // Each query view removes itself and its neighbours at 5 and 10 degrees: between 5 (one
      // view) and 5n views, and all 72 when every view is a query view.
      EXPECT_GE(query.removed_views.size(), std::min<std::size_t>(72, 5));
      EXPECT_LE(query.removed_views.size(), std::min<std::size_t>(72, 5 * n));
      for (double a : query.azimuths) {
        EXPECT_GE(a, 0);
        EXPECT_LT(a, 360);
      }
    }
  }
  EXPECT_EQ(SampleTrial(azimuths, 72, 5).removed_views.size(), 72u);
}

TEST(SampleTrialTest, DeviceAzimuthsCarryOneOffsetAndThreeDegreeNoise) {
  const std::vector<double> azimuths = Coil100Azimuths();
  double sum = 0, sum_sq = 0;
  double first_min = 360, first_max = 0;
  constexpr int kTrials = 4000;
  for (int trial = 0; trial < kTrials; ++trial) {
    const TrialQuery query = SampleTrial(azimuths, 2, TrialSeed(9, 0, 2, trial));
    // The offset cancels in a difference; what is left is the true change plus the difference
    // of two N(0, 3) noises: N(0, 3 * sqrt(2) = 4.24).
    const double measured = AzimuthChange(query.azimuths[0], query.azimuths[1]);
    const double truth = AzimuthChange(azimuths[query.views[0]], azimuths[query.views[1]]);
    const double error = WrapDegrees(measured - truth);
    sum += error;
    sum_sq += error * error;
    first_min = std::min(first_min, query.azimuths[0]);
    first_max = std::max(first_max, query.azimuths[0]);
  }
  EXPECT_NEAR(sum / kTrials, 0, 0.2);
  EXPECT_NEAR(std::sqrt(sum_sq / kTrials), 3 * std::sqrt(2.0), 0.15);
  // The offset is uniform over the circle: the first frame's azimuth goes all round.
  EXPECT_LT(first_min, 5);
  EXPECT_GT(first_max, 355);
}

TEST(SampleTrialTest, IsFixedByTheSeed) {
  const std::vector<double> azimuths = Coil100Azimuths();
  const TrialQuery a = SampleTrial(azimuths, 6, TrialSeed(1, 2, 6, 3));
  const TrialQuery b = SampleTrial(azimuths, 6, TrialSeed(1, 2, 6, 3));
  EXPECT_EQ(a.views, b.views);
  EXPECT_EQ(a.azimuths, b.azimuths);
  EXPECT_EQ(a.removed_views, b.removed_views);
  // Another trial, object or n draws another query.
  EXPECT_NE(a.azimuths, SampleTrial(azimuths, 6, TrialSeed(1, 2, 6, 4)).azimuths);
  EXPECT_NE(a.azimuths, SampleTrial(azimuths, 6, TrialSeed(1, 3, 6, 3)).azimuths);
  EXPECT_NE(TrialSeed(1, 2, 6, 3), TrialSeed(1, 2, 8, 3));
  EXPECT_NE(TrialSeed(1, 2, 6, 3), TrialSeed(2, 2, 6, 3));
}

TEST(SampleTrialTest, RejectsImpossibleQueries) {
  const std::vector<double> azimuths{0, 90, 180};
  EXPECT_THROW(SampleTrial(azimuths, 0, 1), std::invalid_argument);
  EXPECT_THROW(SampleTrial(azimuths, 4, 1), std::invalid_argument);
  const std::vector<double> bad{0, NAN};
  EXPECT_THROW(SampleTrial(bad, 1, 1), std::invalid_argument);
}

TEST(ExcludedViewsTest, RemovesTheNeighboursOfEveryQueryViewOnce) {
  // Views 0 (0 degrees) and 71 (355) are queries, 71 twice: 345..10 degrees go, once each;
  // 15 and 340 stay.
  EXPECT_THAT(ExcludedViews(Coil100Azimuths(), std::vector<int>{71, 0, 71}),
              ElementsAre(0, 1, 2, 69, 70, 71));
}

TEST(NextActiveViewTest, StepsTheWaySuggestedAndOnWhenNone) {
  const std::vector<double> azimuths = Coil100Azimuths();
  int direction = 1;
  // From 350 degrees (view 70), RIGHT 20: 10 degrees, view 2, across 360.
  EXPECT_EQ(NextActiveView(azimuths, 70, SuggestedMove::kRight, 20, direction), 2);
  EXPECT_EQ(direction, 1);
  // LEFT from 10 degrees: 350 again, and the direction becomes -1...
  EXPECT_EQ(NextActiveView(azimuths, 2, SuggestedMove::kLeft, 20, direction), 70);
  EXPECT_EQ(direction, -1);
  // ...which NONE keeps: 350 - 20 = 330, view 66.
  EXPECT_EQ(NextActiveView(azimuths, 70, SuggestedMove::kNone, 20, direction), 66);
  EXPECT_EQ(direction, -1);
  // A step between views lands on the nearest: 30 + 12 = 42 -> 40 (view 8).
  EXPECT_EQ(NextActiveView(azimuths, 6, SuggestedMove::kRight, 12, direction), 8);
}

TEST(WithoutViewsTest, KeepsTheOtherViewsInOrder) {
  ObjectModel model;
  model.id = 7;
  model.name = "cup";
  for (int a : {0, 5, 10, 15, 20}) model.views.push_back({{}, double(a), std::nullopt, 0.1});
  const std::vector<int> removed{0, 2, 3};
  const ObjectModel kept = WithoutViews(model, removed);
  EXPECT_EQ(kept.id, 7);
  EXPECT_EQ(kept.name, "cup");
  ASSERT_EQ(kept.views.size(), 2u);
  EXPECT_EQ(kept.views[0].azimuth, 5);
  EXPECT_EQ(kept.views[1].azimuth, 20);
  const std::vector<int> unsorted{2, 1};
  EXPECT_THROW(WithoutViews(model, unsorted), std::invalid_argument);
  const std::vector<int> outside{5};
  EXPECT_THROW(WithoutViews(model, outside), std::invalid_argument);
}

TEST(IsTopOneHitTest, OnlyTheFirstPlaceCounts) {
  const std::vector<RankedObject> ranking{{4, 0.9}, {7, 0.8}};
  EXPECT_TRUE(IsTopOneHit(ranking, 4));
  EXPECT_FALSE(IsTopOneHit(ranking, 7));
  EXPECT_FALSE(IsTopOneHit({}, 4));
}

}  // namespace
}  // namespace orbit
