// The metrics registry and its text exposition (server/metrics.h), checked against text written
// out by hand from the format's rules
// (https://prometheus.io/docs/instrumenting/exposition_formats/#text-based-format).
#include "server/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

namespace orbit::server {
namespace {

TEST(MetricsTest, CountersExposeHelpTypeAndEscapedLabelsInCreationOrder) {
  MetricsRegistry registry;
  auto& requests = registry.AddCounter("test_requests_total",
                                       "Requests, by path.\nA second line, a \\ and a \"quote\".",
                                       {"path", "method"});
  requests.WithLabels({"/a", "GET"}).Increment();
  requests.WithLabels({"/a", "GET"}).Increment(2);
  requests.WithLabels({"say \"hi\"\\\nbye", "POST"});  // created, never incremented
  registry.AddCounter("test_lonely_total", "Without labels.").WithLabels({}).Increment(7);
  registry.AddCounter("test_unused_total", "A family without children.", {"x"});

  // HELP escapes backslash and line feed only; label values also escape the double quote.
  EXPECT_EQ(registry.Expose(),
            "# HELP test_requests_total Requests, by path.\\nA second line, a \\\\ and a "
            "\"quote\".\n"
            "# TYPE test_requests_total counter\n"
            "test_requests_total{path=\"/a\",method=\"GET\"} 3\n"
            "test_requests_total{path=\"say \\\"hi\\\"\\\\\\nbye\",method=\"POST\"} 0\n"
            "# HELP test_lonely_total Without labels.\n"
            "# TYPE test_lonely_total counter\n"
            "test_lonely_total 7\n");
}

TEST(MetricsTest, WithLabelsGivesOneChildPerDistinctValues) {
  MetricsRegistry registry;
  auto& family = registry.AddCounter("test_total", "t", {"a", "b"});
  Counter& first = family.WithLabels({"x", "y"});
  EXPECT_EQ(&family.WithLabels({"x", "y"}), &first);
  EXPECT_NE(&family.WithLabels({"y", "x"}), &first);
  EXPECT_NE(&family.WithLabels({"x", ""}), &first);
  first.Increment(5);
  EXPECT_EQ(family.WithLabels({"x", "y"}).value(), 5u);
  EXPECT_EQ(family.WithLabels({"y", "x"}).value(), 0u);
}

// Bounds 1e-05, 0.01, 0.25, 2.5, 1e+06 and the observations 0.0078125 (2^-7), 0.25 (on a
// bound: counted in it, since a bucket holds the values <= its bound), 0.5, 3 and 2e6 (above
// every bound). Non-cumulative: 0, 1, 1, 1, 1, and 1 above; cumulative: 0, 1, 2, 3, 4, 5.
// Every partial sum is exact in binary: 0.0078125 + 0.25 + 0.5 + 3 + 2000000 = 2000003.7578125,
// written 2.0000037578125e+06 (exponent 6: Go's 'g' switches to the exponent form there).
TEST(MetricsTest, HistogramExposesCumulativeBucketsInfSumAndCount) {
  MetricsRegistry registry;
  auto& family = registry.AddHistogram("test_latency_seconds", "Latency.", {"op"},
                                       {1e-5, 0.01, 0.25, 2.5, 1e6});
  Histogram& read = family.WithLabels({"read"});
  for (double v : {0.0078125, 0.25, 0.5, 3.0, 2e6}) read.Observe(v);
  family.WithLabels({"write"});  // no observations yet

  EXPECT_EQ(registry.Expose(),
            "# HELP test_latency_seconds Latency.\n"
            "# TYPE test_latency_seconds histogram\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"1e-05\"} 0\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"0.01\"} 1\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"0.25\"} 2\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"2.5\"} 3\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"1e+06\"} 4\n"
            "test_latency_seconds_bucket{op=\"read\",le=\"+Inf\"} 5\n"
            "test_latency_seconds_sum{op=\"read\"} 2.0000037578125e+06\n"
            "test_latency_seconds_count{op=\"read\"} 5\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"1e-05\"} 0\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"0.01\"} 0\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"0.25\"} 0\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"2.5\"} 0\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"1e+06\"} 0\n"
            "test_latency_seconds_bucket{op=\"write\",le=\"+Inf\"} 0\n"
            "test_latency_seconds_sum{op=\"write\"} 0\n"
            "test_latency_seconds_count{op=\"write\"} 0\n");
}

TEST(MetricsTest, HistogramWithoutLabelsHasOnlyLeInItsBuckets) {
  MetricsRegistry registry;
  Histogram& h = registry.AddHistogram("test_seconds", "S.", {}, {1}).WithLabels({});
  h.Observe(0.5);
  h.Observe(1.5);
  EXPECT_EQ(registry.Expose(),
            "# HELP test_seconds S.\n"
            "# TYPE test_seconds histogram\n"
            "test_seconds_bucket{le=\"1\"} 1\n"
            "test_seconds_bucket{le=\"+Inf\"} 2\n"
            "test_seconds_sum 2\n"
            "test_seconds_count 2\n");
  const Histogram::Totals totals = h.Read();
  EXPECT_EQ(totals.cumulative, (std::vector<std::uint64_t>{1, 2}));
  EXPECT_EQ(totals.count, 2u);
  EXPECT_EQ(totals.sum, 2.0);
}

TEST(MetricsTest, GaugesAreReadAtEachExposition) {
  MetricsRegistry registry;
  double queued = 3;
  auto& depth = registry.AddGauge("test_queue_depth", "Tasks waiting.", {"pool"});
  depth.Add({"bulk"}, [&queued] { return queued; });
  depth.Add({"small"}, [] { return 0.25; });
  const std::string header =
      "# HELP test_queue_depth Tasks waiting.\n# TYPE test_queue_depth gauge\n";
  EXPECT_EQ(registry.Expose(),
            header + "test_queue_depth{pool=\"bulk\"} 3\ntest_queue_depth{pool=\"small\"} 0.25\n");
  queued = 12;
  EXPECT_EQ(registry.Expose(),
            header + "test_queue_depth{pool=\"bulk\"} 12\ntest_queue_depth{pool=\"small\"} 0.25\n");
  EXPECT_THROW(depth.Add({"bulk"}, [] { return 1.0; }), std::invalid_argument);
}

TEST(MetricsTest, FamiliesAreExposedInTheOrderTheyWereAdded) {
  MetricsRegistry registry;
  registry.AddGauge("b_gauge", "B.").Add({}, [] { return -1.0; });
  registry.AddCounter("a_total", "A.").WithLabels({});
  EXPECT_EQ(registry.Expose(),
            "# HELP b_gauge B.\n# TYPE b_gauge gauge\nb_gauge -1\n"
            "# HELP a_total A.\n# TYPE a_total counter\na_total 0\n");
}

TEST(MetricsTest, ValuesAreWrittenAsPrometheusGoClientWritesThem) {
  const double inf = std::numeric_limits<double>::infinity();
  const struct {
    double value;
    const char* text;
  } cases[] = {
      {0, "0"},
      {1, "1"},
      {10, "10"},
      {-2.5, "-2.5"},
      {0.005, "0.005"},
      {0.1, "0.1"},
      {1e-5, "1e-05"},
      {2.5e-5, "2.5e-05"},
      {0.0001, "0.0001"},
      {123456, "123456"},
      {1e6, "1e+06"},
      {1234567, "1.234567e+06"},
      {1.0 / 3, "0.3333333333333333"},
      {inf, "+Inf"},
      {-inf, "-Inf"},
      {std::nan(""), "NaN"},
  };
  for (const auto& c : cases) EXPECT_EQ(FormatMetricValue(c.value), c.text) << c.text;
}

TEST(MetricsTest, LabelValuesEscapeBackslashQuoteAndLineFeedOnly) {
  EXPECT_EQ(EscapeLabelValue("plain é\tvalue"), "plain é\tvalue");
  EXPECT_EQ(EscapeLabelValue("a\\b\"c\nd"), "a\\\\b\\\"c\\nd");
  EXPECT_EQ(EscapeLabelValue(""), "");
}

TEST(MetricsTest, RefusesInvalidNamesLabelsAndBounds) {
  MetricsRegistry registry;
  registry.AddCounter("ok_total", "fine", {"a"});
  EXPECT_THROW(registry.AddCounter("ok_total", "again"), std::invalid_argument);
  EXPECT_THROW(registry.AddCounter("1st_total", "digit first"), std::invalid_argument);
  EXPECT_THROW(registry.AddCounter("a-b_total", "dash"), std::invalid_argument);
  EXPECT_THROW(registry.AddCounter("", "empty"), std::invalid_argument);
  EXPECT_NO_THROW(registry.AddCounter("ns:sub_total", "colon allowed"));
  EXPECT_THROW(registry.AddCounter("x_total", "reserved label", {"__name"}), std::invalid_argument);
  EXPECT_THROW(registry.AddCounter("y_total", "twice", {"a", "a"}), std::invalid_argument);
  EXPECT_THROW(registry.AddGauge("z", "bad label", {"a.b"}), std::invalid_argument);
  EXPECT_NO_THROW(registry.AddCounter("le_total", "le is fine outside histograms", {"le"}));
  EXPECT_THROW(registry.AddHistogram("h1", "le", {"le"}, {1}), std::invalid_argument);
  EXPECT_THROW(registry.AddHistogram("h2", "none", {}, {}), std::invalid_argument);
  EXPECT_THROW(registry.AddHistogram("h3", "decreasing", {}, {1, 0.5}), std::invalid_argument);
  EXPECT_THROW(registry.AddHistogram("h4", "repeated", {}, {1, 1}), std::invalid_argument);
  EXPECT_THROW(
      registry.AddHistogram("h5", "infinite", {}, {1, std::numeric_limits<double>::infinity()}),
      std::invalid_argument);
  EXPECT_THROW(registry.AddHistogram("h6", "too many", {}, std::vector<double>(31, 0)),
               std::invalid_argument);
  std::vector<double> thirty;
  for (int i = 1; i <= 30; ++i) thirty.push_back(i);
  EXPECT_NO_THROW(registry.AddHistogram("h7", "thirty", {}, thirty));
  auto& family = registry.AddCounter("two_total", "two labels", {"a", "b"});
  EXPECT_THROW(family.WithLabels({"only one"}), std::invalid_argument);
  EXPECT_THROW(family.WithLabels({"a", "b", "c"}), std::invalid_argument);
}

// Updates from several threads at once lose nothing (relaxed atomics, no lock).
TEST(MetricsTest, ConcurrentUpdatesAreAllCounted) {
  MetricsRegistry registry;
  Counter& counter = registry.AddCounter("c_total", "c").WithLabels({});
  Histogram& histogram = registry.AddHistogram("h_seconds", "h", {}, {0.5}).WithLabels({});
  constexpr int kThreads = 4, kEach = 100000;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kEach; ++i) {
        counter.Increment();
        histogram.Observe(t % 2 == 0 ? 0.25 : 1.0);  // exact in binary: the sum is exact too
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(counter.value(), static_cast<std::uint64_t>(kThreads) * kEach);
  const Histogram::Totals totals = histogram.Read();
  EXPECT_EQ(totals.cumulative[0], 2u * kEach);
  EXPECT_EQ(totals.count, 4u * kEach);
  EXPECT_EQ(totals.sum, 2 * kEach * 0.25 + 2 * kEach * 1.0);
}

}  // namespace
}  // namespace orbit::server
