// Sweeps (evaluation/distortion_sweep.h): the strengths of each axis by hand, the refusals, and
// the table and CSV of a hand-made report.
#include "evaluation/distortion_sweep.h"

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<std::string> Names(const DistortionSweep& sweep) {
  std::vector<std::string> names;
  for (const DistortionSpec& spec : sweep.distortions) names.push_back(spec.name);
  return names;
}

TEST(DistortionSweepTest, DefaultRangesAreTheIssuesEndsEvenlySpaced) {
  // gn: (0.03 - 0.002) / 5 = 0.0056 apart.
  const DistortionSweep gn = ParseSweep("gn", 6);
  EXPECT_EQ(gn.axis, "gn");
  EXPECT_EQ(gn.strength, "noise variance");
  EXPECT_THAT(Names(gn), ElementsAre("gn:var=0.002", "gn:var=0.0076", "gn:var=0.0132",
                                     "gn:var=0.0188", "gn:var=0.0244", "gn:var=0.03"));
  // mb: lengths 4 px apart, the angle 37 degrees further at each step, modulo 180.
  EXPECT_THAT(Names(ParseSweep("mb", 6)),
              ElementsAre("mb:len=5:angle=0", "mb:len=9:angle=37", "mb:len=13:angle=74",
                          "mb:len=17:angle=111", "mb:len=21:angle=148", "mb:len=25:angle=5"));
  EXPECT_THAT(ParseSweep("jpeg", 6).strengths, ElementsAre(10, 20, 30, 40, 50, 60));
  EXPECT_THAT(ParseSweep("gain", 3).strengths, ElementsAre(0.6, 1.0, 1.4));
}

TEST(DistortionSweepTest, ACustomRangeAndWholeQualitiesWithoutRepeats) {
  EXPECT_THAT(ParseSweep("gn:0.01..0.05", 5).strengths, ElementsAre(0.01, 0.02, 0.03, 0.04, 0.05));
  // 10, 10.4, 10.8, 11.2, 11.6, 12 round to 10, 10, 11, 11, 12, 12: each quality once.
  EXPECT_THAT(Names(ParseSweep("jpeg:10..12", 6)),
              ElementsAre("jpeg:q=10", "jpeg:q=11", "jpeg:q=12"));
}

TEST(DistortionSweepTest, RefusesMalformedSweepsNamingThem) {
  const auto error = [](const std::string& text, int steps = 6) {
    return testing::ErrorMessageOf([&] { ParseSweep(text, steps); });
  };
  EXPECT_EQ(error("blur"), "\"blur\": unknown axis \"blur\" (mb, gn, jpeg, gain)");
  EXPECT_EQ(error("gn:0.5..0.1"), "\"gn:0.5..0.1\": FROM must be below TO");
  EXPECT_EQ(error("gn:0.01-0.03"), "\"gn:0.01-0.03\": the range must read FROM..TO");
  EXPECT_EQ(error("gn:0..x"), "\"gn:0..x\": \"x\" is not a number");
  EXPECT_EQ(error("gn:0..2"), "\"gn:0..2\": noise variance must be in 0..1");
  EXPECT_EQ(error("jpeg", 1), "\"jpeg\": steps must be in 2..20, got 1");
  EXPECT_EQ(error("jpeg", 21), "\"jpeg\": steps must be in 2..20, got 21");
}

TEST(DistortionSweepTest, TableAndCsvGiveHitRateAgainstStrength) {
  const std::vector<DistortionSweep> sweeps{ParseSweep("gn", 2)};  // 0.002 and 0.03
  EvaluationReport report;
  const auto cell = [](std::string distortion, int n, int hits) {
    EvaluationCell c;
    c.method = "product";
    c.variant = DescriptorVariant::kCeddRobust;
    c.distortion = std::move(distortion);
    c.n = n;
    c.trials = 10;
    c.hits = hits;
    return c;
  };
  report.cells = {cell("df", 8, 10), cell("gn:var=0.002", 8, 9), cell("gn:var=0.03", 8, 7)};

  EXPECT_EQ(SweepMarkdown(report, sweeps),
            "### Sweep: noise variance (hit rate %, top-1)\n\n"
            "| method | n | 0.002 | 0.03 | worst |\n"
            "|---|---:|---:|---:|---:|\n"
            "| product (cedd-robust) | 8 | 90.0 | 70.0 | 70.0 |\n\n");
  std::ostringstream csv;
  WriteSweepCsv(report, sweeps, csv);
  EXPECT_EQ(csv.str(),
            "axis,strength,distortion,method,variant,n,trials,hits,hit_rate\n"
            "gn,0.002,gn:var=0.002,product,cedd-robust,8,10,9,0.9000\n"
            "gn,0.03,gn:var=0.03,product,cedd-robust,8,10,7,0.7000\n");
  const cv::Mat plot = DrawSweepPlot(report, sweeps);
  EXPECT_EQ(plot.type(), CV_8UC3);
  EXPECT_GE(plot.cols, 460);                 // one sweep: one panel (or two legend entries) wide
  EXPECT_EQ(plot.rows, 40 + 340 + 26 + 12);  // title, one n: one row of panels, one legend row
}

}  // namespace
}  // namespace orbit
