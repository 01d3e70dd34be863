// SummaryGraph: hnswlib's graph behind the view index's object candidates. Distances checked by
// hand for each metric (the byte metric's rounding included), and searches against a brute-force
// scan by the graph's own distance.
#include "core/index/summary_graph.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/base/cpu_dispatch.h"

namespace orbit {
namespace {

using Metric = SummaryGraph::Metric;

SummaryGraph Graph(Metric metric, std::size_t dimensions, std::size_t capacity) {
  return SummaryGraph(dimensions, capacity, {.metric = metric});
}

TEST(SummaryGraphTest, CosineDistancesByHand) {
  const SummaryGraph graph = Graph(Metric::kCosine, 2, 1);
  const float x[] = {1, 0}, diagonal[] = {1, 1}, a[] = {1, 2}, b[] = {2, 1}, zero[] = {0, 0};
  EXPECT_NEAR(graph.Distance(x, diagonal), 1 - 1 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(graph.Distance(a, b), 1 - 0.8, 1e-6);  // (2 + 2) / 5
  EXPECT_NEAR(graph.Distance(a, a), 0, 1e-6);
  EXPECT_NEAR(graph.Distance(a, zero), 1, 1e-6);
}

TEST(SummaryGraphTest, ByteCosineDistancesByHandWithTheirRounding) {
  const SummaryGraph graph = Graph(Metric::kCosineBytes, 2, 1);
  // Values that are 0 or the vector's largest are kept exactly: (127, 0) and (127, 127).
  const float x[] = {1, 0}, diagonal[] = {1, 1};
  EXPECT_NEAR(graph.Distance(x, diagonal), 1 - 1 / std::sqrt(2.0), 1e-6);
  // (1, 2) is kept as (64, 127) with scale 2 / sqrt(5) / 127 (63.5 rounds away from zero), and
  // (2, 1) as (127, 64): the cosine reads 0.8 * (64 * 127 * 2) / 127^2 = 0.8 * 16256 / 16129.
  const float a[] = {1, 2}, b[] = {2, 1};
  EXPECT_NEAR(graph.Distance(a, b), 1 - 0.8 * 16256.0 / 16129.0, 1e-6);
  // A zero vector is at distance 1 from everything.
  const float zero[] = {0, 0};
  EXPECT_NEAR(graph.Distance(a, zero), 1, 1e-6);
}

TEST(SummaryGraphTest, EuclideanDistanceIsTheSquaredL2) {
  const SummaryGraph graph = Graph(Metric::kEuclidean, 2, 1);
  const float a[] = {1, 2}, b[] = {4, 6};
  EXPECT_NEAR(graph.Distance(a, b), 25, 1e-6);
}

TEST(SummaryGraphTest, ByteDistancesAreTheSameOnBothHotLoopPaths) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0, 7);
  const SummaryGraph graph = Graph(Metric::kCosineBytes, 144, 1);
  std::vector<float> a(144), b(144);
  for (int trial = 0; trial < 50; ++trial) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      a[i] = value(random);
      b[i] = value(random);
    }
    TEST_SetHotLoopPath(HotLoopPath::kPortable);
    const double portable = graph.Distance(a.data(), b.data());
    TEST_SetHotLoopPath(HotLoopPath::kFastest);
    EXPECT_EQ(graph.Distance(a.data(), b.data()), portable);
  }
}

// Sector-mean-like points: non-negative, most values small, a few large.
std::vector<std::vector<float>> Points(std::size_t count, std::size_t dimensions, unsigned seed) {
  std::mt19937 random(seed);
  std::exponential_distribution<float> value(1.0f);
  std::vector<std::vector<float>> points(count, std::vector<float>(dimensions));
  for (auto& point : points) {
    for (float& v : point) v = std::min(7.0f, value(random));
  }
  return points;
}

// The labels of the `count` points nearest `query` by the graph's distance, nearest last.
std::vector<std::size_t> BruteForce(const SummaryGraph& graph,
                                    const std::vector<std::vector<float>>& points,
                                    const std::vector<float>& query, std::size_t count) {
  std::vector<std::pair<double, std::size_t>> scored;
  for (std::size_t p = 0; p < points.size(); ++p) {
    scored.emplace_back(graph.Distance(points[p].data(), query.data()), p);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::size_t> labels;
  for (std::size_t k = std::min(count, scored.size()); k-- > 0;) labels.push_back(scored[k].second);
  return labels;
}

TEST(SummaryGraphTest, ABroadSearchFindsWhatAScanFindsNearestLast) {
  const std::size_t dimensions = 48, count = 400;
  const auto points = Points(count, dimensions, 11);
  const auto queries = Points(20, dimensions, 12);
  for (const Metric metric : {Metric::kCosine, Metric::kCosineBytes, Metric::kEuclidean}) {
    SummaryGraph graph = Graph(metric, dimensions, count);
    for (std::size_t p = 0; p < count; ++p) graph.Add(points[p].data(), p);
    graph.SetBreadth(count);  // the whole graph: exact
    std::vector<std::size_t> found;
    for (const auto& query : queries) {
      graph.Search(query.data(), 10, found);
      EXPECT_EQ(found, BruteForce(graph, points, query, 10)) << static_cast<int>(metric);
    }
  }
}

TEST(SummaryGraphTest, AskingForMoreThanItHoldsGivesEveryPointAndAnEmptyGraphNone) {
  const auto points = Points(5, 16, 3);
  SummaryGraph graph = Graph(Metric::kCosineBytes, 16, 10);
  std::vector<std::size_t> found = {99};
  graph.Search(points[0].data(), 3, found);
  EXPECT_TRUE(found.empty());
  for (std::size_t p = 0; p < points.size(); ++p) graph.Add(points[p].data(), 100 + p);
  graph.Search(points[0].data(), 10, found);
  ASSERT_EQ(found.size(), 5u);
  EXPECT_EQ(found.back(), 100u);  // the query is point 0 itself
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<std::size_t>{100, 101, 102, 103, 104}));
}

TEST(SummaryGraphTest, BytesKeepAboutAQuarterOfTheFloatsVectors) {
  const std::size_t dimensions = 144, count = 200;
  const auto points = Points(count, dimensions, 5);
  SummaryGraph floats = Graph(Metric::kCosine, dimensions, count);
  SummaryGraph bytes = Graph(Metric::kCosineBytes, dimensions, count);
  for (std::size_t p = 0; p < count; ++p) {
    floats.Add(points[p].data(), p);
    bytes.Add(points[p].data(), p);
  }
  // Per point the vectors shrink from 144 floats to one float and 144 bytes; the links stay.
  const double saved = (floats.Bytes() - bytes.Bytes()) / static_cast<double>(count);
  EXPECT_NEAR(saved, 144 * 4 - (4 + 144), 1.0);
}

}  // namespace
}  // namespace orbit
