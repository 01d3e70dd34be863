#include "cli/latency_histogram.h"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(LatencyHistogramTest, AnEmptyHistogramReportsZeros) {
  const LatencyHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.min(), 0);
  EXPECT_EQ(h.max(), 0);
  EXPECT_EQ(h.mean(), 0);
  EXPECT_EQ(h.Percentile(50), 0);
  EXPECT_EQ(h.Percentile(100), 0);
}

// Below 128 us every value has a bucket of its own: nearest-rank percentiles are exact.
TEST(LatencyHistogramTest, SmallValuesGiveExactNearestRankPercentiles) {
  LatencyHistogram h;
  for (int v = 100; v >= 1; --v) h.Record(v);  // order does not matter
  EXPECT_EQ(h.count(), 100u);
  EXPECT_EQ(h.min(), 1);
  EXPECT_EQ(h.max(), 100);
  EXPECT_DOUBLE_EQ(h.mean(), 50.5);
  EXPECT_EQ(h.Percentile(50), 50);  // the 50th of 100 values
  EXPECT_EQ(h.Percentile(90), 90);
  EXPECT_EQ(h.Percentile(99), 99);  // 99 x 100 / 100 = 99 exactly, not 100
  EXPECT_EQ(h.Percentile(99.5), 100);
  EXPECT_EQ(h.Percentile(100), 100);
  EXPECT_EQ(h.Percentile(0.5), 1);  // rank ceil(0.5) = 1

  LatencyHistogram four;
  for (int v : {10, 20, 30, 40}) four.Record(v);
  EXPECT_EQ(four.Percentile(50), 20);  // rank 2 of 4
  EXPECT_EQ(four.Percentile(51), 30);  // rank ceil(2.04) = 3
  EXPECT_EQ(four.Percentile(75), 30);
  EXPECT_EQ(four.Percentile(76), 40);
}

// Above 128 us a value falls in a bucket 1/64 of its power of two wide, reported by its middle.
TEST(LatencyHistogramTest, LargeValuesAreReportedByTheMiddleOfTheirBucket) {
  LatencyHistogram h;
  for (int v = 1000; v <= 1999; ++v) h.Record(v);
  // Ranks 500, 900 and 990 of 1000 are the values 1499, 1899 and 1989.
  // 1499 has 11 bits: buckets of 2^(11-7) = 16 us; 1499 / 16 = 93, so [1488, 1503], middle 1495.5.
  EXPECT_DOUBLE_EQ(h.Percentile(50), 1495.5);
  // 1899 / 16 = 118: [1888, 1903], middle 1895.5. 1989 / 16 = 124: [1984, 1999], middle 1991.5.
  EXPECT_DOUBLE_EQ(h.Percentile(90), 1895.5);
  EXPECT_DOUBLE_EQ(h.Percentile(99), 1991.5);
  EXPECT_EQ(h.Percentile(100), 1999);  // max, exactly
  EXPECT_EQ(h.min(), 1000);
  EXPECT_DOUBLE_EQ(h.mean(), 1499.5);
}

TEST(LatencyHistogramTest, ATailDoesNotMoveTheMedianAndMaxIsExact) {
  LatencyHistogram h;
  for (int i = 0; i < 99; ++i) h.Record(1000);  // 1 ms
  h.Record(1000000);                            // one 1 s outlier
  // 1000 has 10 bits: buckets of 8 us; 1000 / 8 = 125, so [1000, 1007], middle 1003.5.
  EXPECT_DOUBLE_EQ(h.Percentile(50), 1003.5);
  EXPECT_DOUBLE_EQ(h.Percentile(99), 1003.5);  // rank 99 is still 1 ms
  // Rank 100 of 100 is the last: the max, exactly (not its bucket's middle, 1003519.5).
  EXPECT_EQ(h.Percentile(99.9), 1000000);
  EXPECT_EQ(h.max(), 1000000);
}

TEST(LatencyHistogramTest, EveryPercentileIsWithinOnePercentOfTheTrueValue) {
  for (double v = 1; v < 1e12; v *= 1.07) {
    const auto value = static_cast<std::int64_t>(v);
    LatencyHistogram h;
    h.Record(value);
    h.Record(value * 4);  // so that the median is not clamped to an exact max
    const double reported = h.Percentile(50);
    EXPECT_LE(std::abs(reported - value), 0.008 * value) << value;
  }
}

TEST(LatencyHistogramTest, MergingGivesTheHistogramOfAllValues) {
  LatencyHistogram a, b, all;
  for (int v = 0; v < 5000; v += 7) {
    (v % 2 ? a : b).Record(v);
    all.Record(v);
  }
  LatencyHistogram empty;
  a.Merge(empty);
  a.Merge(b);
  EXPECT_EQ(a.count(), all.count());
  EXPECT_EQ(a.min(), all.min());
  EXPECT_EQ(a.max(), all.max());
  EXPECT_DOUBLE_EQ(a.mean(), all.mean());
  for (double p : {1.0, 50.0, 90.0, 99.0, 99.9, 100.0}) {
    EXPECT_EQ(a.Percentile(p), all.Percentile(p)) << p;
  }
  empty.Merge(all);
  EXPECT_EQ(empty.min(), 0);
  EXPECT_EQ(empty.Percentile(90), all.Percentile(90));
}

TEST(LatencyHistogramTest, ANegativeDurationCountsAsZero) {
  LatencyHistogram h;
  h.Record(-5);
  h.Record(3);
  EXPECT_EQ(h.min(), 0);
  EXPECT_EQ(h.Percentile(50), 0);
  EXPECT_EQ(h.max(), 3);
}

}  // namespace
}  // namespace orbit
