// The recognition reports of `orbit eval` on a hand-made report whose every figure is counted
// by hand below.
#include "evaluation/recognition_report.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

QueryVerdict Known(bool hit, Decision decision, double p, double confidence, double pose_error) {
  QueryVerdict v;
  v.known = true;
  v.hit = hit;
  v.object = "cup1";
  v.answer = hit ? "cup1" : "cup \"3\", white";  // a name that needs quoting in CSV
  v.decision = decision;
  v.unknown_p_value = p;
  v.confidence = confidence;
  v.noise_sigma = 24.5;  // the window's mean readings
  v.blur = 0.625;
  if (hit) {
    v.pose_error = pose_error;
    v.pose_spread = 0;
  }
  return v;
}

QueryVerdict Unknown(Decision decision, double p, double confidence) {
  QueryVerdict v;
  v.object = "apple10";
  v.answer = "apple2";
  v.decision = decision;
  v.unknown_p_value = p;
  v.confidence = confidence;
  return v;
}

// One product cell, DF, n = 8: four known queries and two unknown ones.
//   known: right+accepted (p 0.01, conf 0.95, pose 10), right+accepted (p 0.1, conf 0.92,
//          pose 30), right+rejected (p 0.5, conf 0.4, pose 20), wrong+accepted (p 0.05,
//          conf 0.85)
//   unknown: rejected (p 0.6, conf 0.1), accepted (p 0.02, conf 0.88)
EvaluationReport HandMadeReport() {
  EvaluationCell cell;
  cell.method = "product";
  cell.variant = DescriptorVariant::kCeddRobust;
  cell.distortion = "df";
  cell.n = 8;
  cell.verdicts = {Known(true, Decision::kAccept, 0.01, 0.95, 10),
                   Known(true, Decision::kAccept, 0.1, 0.92, 30),
                   Known(true, Decision::kUnknown, 0.5, 0.4, 20),
                   Known(false, Decision::kAccept, 0.05, 0.85, 0),
                   Unknown(Decision::kUnknown, 0.6, 0.1),
                   Unknown(Decision::kAccept, 0.02, 0.88)};
  cell.trials = 4;
  cell.hits = 3;
  cell.accepted = 2;
  cell.accepted_wrong = 1;
  cell.unknown_trials = 2;
  cell.rejected = 1;
  EvaluationReport report;
  report.cells.push_back(cell);
  report.unknown_objects = 1;
  return report;
}

TEST(RecognitionReportTest, CountsEachOutcomeAndThePoseErrors) {
  const std::string markdown = RecognitionMarkdown(HandMadeReport());
  // 2 of 4 right+accepted, 1 rejected, 1 accepted wrong; 1 of 2 unknown rejected; pose errors
  // 10, 20, 30: median 20, 90th percentile (nearest rank 3 of 3) 30.
  EXPECT_NE(markdown.find("| product | cedd-robust | DF | 8 | 50.0 | 25.0 | 25.0 | 50.0 | 50.0 | "
                          "20.0 | 30.0 |"),
            std::string::npos)
      << markdown;
}

TEST(RecognitionReportTest, BinsConfidenceAgainstRightAnswers) {
  const EvaluationReport report = HandMadeReport();
  const std::vector<ReliabilityBin> bins = Reliability({&report.cells[0]});
  ASSERT_EQ(bins.size(), 10u);
  // 0.9-1.0: conf 0.95 and 0.92, both right.
  EXPECT_EQ(bins[9].updates, 2);
  EXPECT_EQ(bins[9].right, 2);
  EXPECT_NEAR(bins[9].mean_confidence, 0.935, 1e-12);
  // 0.8-0.9: 0.85 (wrong) and 0.88 (an unknown object, wrong).
  EXPECT_EQ(bins[8].updates, 2);
  EXPECT_EQ(bins[8].right, 0);
  // 0.4-0.5: the rejected right answer counts as right: its top-1 object was right.
  EXPECT_EQ(bins[4].updates, 1);
  EXPECT_EQ(bins[4].right, 1);
  EXPECT_EQ(bins[1].updates, 1);
  EXPECT_EQ(bins[0].updates, 0);
}

// The hand-made bins' gaps, 100 x (right share - mean confidence): 0.9-1.0 (2 updates)
// 100 - 93.5 = +6.5; 0.8-0.9 (2) 0 - 86.5 = -86.5; 0.4-0.5 (1) 100 - 40 = +60; 0.1-0.2 (1)
// 0 - 10 = -10.
TEST(RecognitionReportTest, NamesTheBinFarthestFromTheShareRight) {
  const EvaluationReport report = HandMadeReport();
  const std::vector<ReliabilityBin> bins = Reliability({&report.cells[0]});
  const std::optional<ReliabilityGap> any = LargestReliabilityGap(bins, 1);
  ASSERT_TRUE(any.has_value());
  EXPECT_DOUBLE_EQ(any->bin.low, 0.8);
  EXPECT_NEAR(any->points, -86.5, 1e-9);
  // Bins of at least 3 updates: none.
  EXPECT_FALSE(LargestReliabilityGap(bins, 3).has_value());
  // The report's own threshold is 100 updates: six say too little, and the report says so.
  const std::string markdown = ReliabilityMarkdown(report);
  EXPECT_NE(markdown.find("No bin holds 100 updates: too few to judge the confidence by."),
            std::string::npos)
      << markdown;
  // 100 copies of the cell: every bin that held updates holds 100 or more, the same gaps.
  EvaluationReport many = report;
  for (int copy = 1; copy < 100; ++copy) many.cells.push_back(report.cells[0]);
  const std::string many_markdown = ReliabilityMarkdown(many);
  EXPECT_NE(many_markdown.find("Farthest from the share right, of the bins of at least 100 "
                               "updates: 0.8-0.9, -86.5 points (share right less mean "
                               "confidence)."),
            std::string::npos)
      << many_markdown;
}

// Ten unknown queries with U = 1, 2, ..., 10; six known queries: right with U 0.5, 1.5, 2.0,
// 2.5 and 12, wrong with U 0.2 (it never counts: it is not answered right).
//   area: 0.5 lies below all 10 unknown U, 1.5 below 9, 2.0 below 8 and ties 1 (half), 2.5
//         below 8, 12 below none: (10 + 9 + 8.5 + 8 + 0) / (5 x 10) = 0.71;
//   95% rejected: no unknown accepted, below 1: 0.5 (1 of 6 known queries, 16.7%);
//   90%: one accepted, below 2: 0.5, 1.5 (33.3%); 80% and 75%: two, below 3: 0.5, 1.5, 2.0,
//   2.5 (66.7%).
TEST(RecognitionReportTest, SaysWhatAThresholdOnTheUnknownStatisticCouldDo) {
  EvaluationCell cell;
  cell.method = "product";
  cell.variant = DescriptorVariant::kCeddRobust;
  cell.distortion = "df";
  cell.n = 8;
  for (const double u : {0.5, 1.5, 2.0, 2.5, 12.0}) {
    cell.verdicts.push_back(Known(true, Decision::kAccept, 0.1, 0.9, 0));
    cell.verdicts.back().unknown_statistic = u;
  }
  cell.verdicts.push_back(Known(false, Decision::kAccept, 0.1, 0.9, 0));
  cell.verdicts.back().unknown_statistic = 0.2;
  for (int u = 1; u <= 10; ++u) {
    cell.verdicts.push_back(Unknown(Decision::kUnknown, 0.5, 0.2));
    cell.verdicts.back().unknown_statistic = u;
  }
  const std::optional<UnknownSeparation> separation = SeparationOf(cell);
  ASSERT_TRUE(separation.has_value());
  EXPECT_NEAR(separation->area, 0.71, 1e-12);
  ASSERT_EQ(separation->known_right.size(), 4u);
  EXPECT_NEAR(separation->known_right[0], 1.0 / 6, 1e-12);
  EXPECT_NEAR(separation->known_right[1], 2.0 / 6, 1e-12);
  EXPECT_NEAR(separation->known_right[2], 4.0 / 6, 1e-12);
  EXPECT_NEAR(separation->known_right[3], 4.0 / 6, 1e-12);
  EvaluationReport report;
  report.cells.push_back(cell);
  const std::string markdown = SeparationMarkdown(report);
  EXPECT_NE(markdown.find("| product | cedd-robust | DF | 8 | 0.710 | 16.7 | 33.3 | 66.7 | 66.7 |"),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("| 95% rejected | 90% rejected | 80% rejected | 75% rejected |"),
            std::string::npos)
      << markdown;
  // A server's answers state no U, and a cell without unknown queries has nothing to separate.
  EvaluationCell server = cell;
  server.verdicts[3].unknown_statistic = std::nan("");
  EXPECT_FALSE(SeparationOf(server).has_value());
  EvaluationCell known_only = cell;
  known_only.verdicts.resize(6);
  EXPECT_FALSE(SeparationOf(known_only).has_value());
  report.cells = {server, known_only};
  EXPECT_EQ(SeparationMarkdown(report), "");
}

TEST(RecognitionReportTest, SweepsTheTargetRate) {
  const LineFigure figure = RecognitionCurves(HandMadeReport());
  ASSERT_EQ(figure.panels.size(), 1u);
  ASSERT_EQ(figure.panels[0].series.size(), 1u);
  const auto& points = figure.panels[0].series[0].points;
  ASSERT_EQ(points.size(), 13u);
  // t = 0.001: nothing accepted. t = 0.01 (index 1): 1 of 4 known right, 0 of 2 unknown.
  EXPECT_EQ(points[0], std::make_pair(0.0, 0.0));
  EXPECT_EQ(points[1], std::make_pair(0.0, 0.25));
  // t = 0.02: the unknown at 0.02 joins. t = 0.1 (index 4): known right 0.01 and 0.1.
  EXPECT_EQ(points[2], std::make_pair(0.5, 0.25));
  EXPECT_EQ(points[4], std::make_pair(0.5, 0.5));
  // t = 1: every right answer and every unknown accepted.
  EXPECT_EQ(points[12], std::make_pair(1.0, 0.75));
  EvaluationReport known_only = HandMadeReport();
  known_only.cells[0].unknown_trials = 0;
  EXPECT_THROW(RecognitionCurves(known_only), std::invalid_argument);
}

TEST(RecognitionReportTest, WritesOneCsvLinePerQuery) {
  std::ostringstream out;
  WriteVerdictsCsv(HandMadeReport(), out);
  std::istringstream lines(out.str());
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line,
            "method,variant,distortion,n,object,answer,known,hit,decision,unknown_statistic,"
            "unknown_p_value,confidence,pose_error,pose_spread,noise_sigma,blur");
  std::getline(lines, line);
  EXPECT_EQ(line,
            "product,cedd-robust,df,8,cup1,cup1,1,1,ACCEPT,0,0.01,0.95,10.0,0.0,24.500,0.625");
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 5u);
  // The wrong answer: which object the query was taken for, quoted as RFC 4180 says.
  EXPECT_EQ(rows[2],
            "product,cedd-robust,df,8,cup1,\"cup \"\"3\"\", white\",1,0,ACCEPT,0,0.05,0.85,,,"
            "24.500,0.625");
  // An unknown query: no pose, no readings.
  EXPECT_EQ(rows[4], "product,cedd-robust,df,8,apple10,apple2,0,0,ACCEPT,0,0.02,0.88,,,,");
}

}  // namespace
}  // namespace orbit
