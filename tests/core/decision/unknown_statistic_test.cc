// UnknownStatistic against values computed by hand from the formula in the header.
#include "core/decision/unknown_statistic.h"

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/hand_made_descriptors.h"

namespace orbit {
namespace {

using testing::Bins;

IndexedObject Object(ObjectId id, std::vector<std::pair<DescriptorValues, double>> views) {
  ObjectModel model;
  model.id = id;
  model.name = "obj" + std::to_string(id);
  double azimuth = 0;
  for (const auto& [descriptor, typical] : views) {
    model.views.push_back({descriptor, azimuth, std::nullopt, typical});
    azimuth += 90;
  }
  return IndexedObject(std::move(model));
}

QueryFrame Frame(const DescriptorValues& values) {
  return {{DescriptorVariant::kCeddLire, values}, std::nullopt};
}

const DescriptorValues kQuery = Bins({{0, 4}});         // q.q = 16
const DescriptorValues kHalf = Bins({{0, 4}, {1, 4}});  // q.v = 16, v.v = 32: TC 1/2
const DescriptorValues kDisjoint = Bins({{1, 4}});      // TC 0

TEST(UnknownStatisticTest, IsZeroWhenTheFramesAreTheWinnersViews) {
  const IndexedObject winner = Object(1, {{kQuery, 0.1}, {kDisjoint, 0.1}});
  const IndexedObject runner_up = Object(2, {{kHalf, 0.1}});
  const std::vector<QueryFrame> window{Frame(kQuery), Frame(kQuery)};
  EXPECT_DOUBLE_EQ(UnknownStatistic(window, winner, &runner_up), 0.0);
}

TEST(UnknownStatisticTest, WeighsTheRunnerUpAndTheTypicalDistance) {
  // d1 = 1 - 1/2 = 0.5 (best view kHalf, Ttyp 0.25); d2 = 1 - 0 = 1.
  // U = 0.5 / 1 + 0.2 * 0.5 / 0.25 = 0.9.
  const IndexedObject winner = Object(1, {{kDisjoint, 0.9}, {kHalf, 0.25}});
  const IndexedObject runner_up = Object(2, {{kDisjoint, 0.1}});
  const std::vector<QueryFrame> window{Frame(kQuery)};
  EXPECT_NEAR(UnknownStatistic(window, winner, &runner_up), 0.9, 1e-12);
  // No runner-up counts d2 = 1: the same here.
  EXPECT_NEAR(UnknownStatistic(window, winner, nullptr), 0.9, 1e-12);
  // A runner-up as close as the winner: ratio 1, U = 1 + 0.4.
  const IndexedObject twin = Object(3, {{kHalf, 0.25}});
  EXPECT_NEAR(UnknownStatistic(window, winner, &twin), 1.4, 1e-12);
}

TEST(UnknownStatisticTest, AFrameBetweenTwoNeighbouringViewsIsAsNearAsTheirBlend) {
  // The frame is the mean of two views 90 degrees apart: TC 1 with their blend, 18/20 = 0.9
  // with either view (q.q = 18, a.a = 20, q.a = 18).
  const DescriptorValues a = Bins({{0, 4}, {1, 2}});
  const DescriptorValues b = Bins({{0, 4}, {2, 2}});
  const std::vector<QueryFrame> window{Frame(Bins({{0, 4}, {1, 1}, {2, 1}}))};
  const IndexedObject neighbours = Object(1, {{a, 0.1}, {b, 0.1}});  // at 0 and 90
  EXPECT_NEAR(UnknownStatistic(window, neighbours, nullptr), 0.0, 1e-7);
  // With a third view between them (0, 90, 180) the two are not neighbours: the best is a view,
  // d1 = 0.1, U = 0.1 / 1 + 0.2 * 0.1 / 0.1 = 0.3. (The blends with the view between, kDisjoint,
  // reach 11/20 and 11/16.)
  const IndexedObject apart = Object(2, {{a, 0.1}, {kDisjoint, 0.1}, {b, 0.1}});
  EXPECT_NEAR(UnknownStatistic(window, apart, nullptr), 0.3, 1e-6);
}

TEST(UnknownStatisticTest, DropsTheTypicalTermWithoutTypicalDistances) {
  const IndexedObject winner = Object(1, {{kHalf, 0.0}});
  const std::vector<QueryFrame> window{Frame(kQuery)};
  EXPECT_NEAR(UnknownStatistic(window, winner, nullptr), 0.5, 1e-12);
}

TEST(UnknownStatisticTest, AveragesDistancesOverTheWindowBeforeDividing) {
  // Frame 1: d1 = 0, d2 = 1, t = 0.2 (kQuery's view). Frame 2 (kHalf): its best view is kHalf
  // itself, d1 = 0, so both frames match exactly: U = 0.
  const IndexedObject winner = Object(1, {{kQuery, 0.2}, {kHalf, 0.2}});
  const std::vector<QueryFrame> exact{Frame(kQuery), Frame(kHalf)};
  EXPECT_DOUBLE_EQ(UnknownStatistic(exact, winner, nullptr), 0.0);
  // Frames kQuery and kDisjoint against a winner holding only kQuery: d1 = 0 and 1, d2 = 1 and
  // 1, t = 0.2 and 0.2: U = (1 / 2) / (2 / 2) + 0.2 * 1 / 0.4 = 0.5 + 0.5 = 1.
  const IndexedObject single = Object(1, {{kQuery, 0.2}});
  const std::vector<QueryFrame> mixed{Frame(kQuery), Frame(kDisjoint)};
  EXPECT_NEAR(UnknownStatistic(mixed, single, nullptr), 1.0, 1e-12);
}

TEST(UnknownStatisticTest, RefusesAnEmptyWindow) {
  const IndexedObject winner = Object(1, {{kQuery, 0.1}});
  EXPECT_THROW(UnknownStatistic({}, winner, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
