// Distractor sweeps (evaluation/distractor_sweep.h): the table, CSV and plot of hand-made reports,
// their numbers worked out by hand, and the refusal of reports that are not one sweep.
#include "evaluation/distractor_sweep.h"

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace orbit {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

EvaluationCell Cell(std::string distortion, int hits, int rejected) {
  EvaluationCell cell;
  cell.method = "product";
  cell.variant = DescriptorVariant::kCeddHsvHog;
  cell.distortion = std::move(distortion);
  cell.n = 4;
  cell.trials = 200;
  cell.hits = hits;
  cell.unknown_trials = 40;
  cell.rejected = rejected;
  return cell;
}

// Hits of 200 known queries and rejections of 40 unknown ones, for DF then GN.
EvaluationReport Report(std::size_t distractors, int df_hits, int df_rejected, int gn_hits,
                        int gn_rejected) {
  EvaluationReport report;
  report.distractors = distractors;
  report.seed = 1;
  report.cells = {Cell("df", df_hits, df_rejected), Cell("gn", gn_hits, gn_rejected)};
  return report;
}

TEST(DistractorSweepTest, TableAndCsvGiveHitsAndRejectionsAgainstTheCount) {
  const std::vector<EvaluationReport> sweep{Report(0, 200, 30, 190, 34),
                                            Report(9900, 199, 27, 181, 33)};
  // 199 / 200 = 99.5%, 27 / 40 = 67.5%, 181 / 200 = 90.5%, 33 / 40 = 82.5%.
  EXPECT_EQ(DistractorSweepMarkdown(sweep),
            "### cedd-hsv-hog: against the number of distractors, hit rate (%) and unknown "
            "objects rejected (%)\n\n"
            "| distortion | method | n | hits, 0 | hits, 9900 | unknowns, 0 | unknowns, 9900 |\n"
            "|---|---|---:|---:|---:|---:|---:|\n"
            "| df | product | 4 | 100.0 | 99.5 | 75.0 | 67.5 |\n"
            "| gn | product | 4 | 95.0 | 90.5 | 85.0 | 82.5 |\n\n");
  std::ostringstream csv;
  WriteDistractorSweepCsv(sweep, csv);
  EXPECT_EQ(csv.str(),
            "distractors,method,variant,distortion,n,trials,hits,hit_rate,unknown_trials,rejected,"
            "reject_rate\n"
            "0,product,cedd-hsv-hog,df,4,200,200,1.0000,40,30,0.7500\n"
            "0,product,cedd-hsv-hog,gn,4,200,190,0.9500,40,34,0.8500\n"
            "9900,product,cedd-hsv-hog,df,4,200,199,0.9950,40,27,0.6750\n"
            "9900,product,cedd-hsv-hog,gn,4,200,181,0.9050,40,33,0.8250\n");
}

TEST(DistractorSweepTest, WithoutUnknownObjectsOnlyHitsAreShown) {
  std::vector<EvaluationReport> sweep{Report(0, 200, 0, 190, 0), Report(1000, 198, 0, 188, 0)};
  for (EvaluationReport& report : sweep) {
    for (EvaluationCell& cell : report.cells) cell.unknown_trials = 0;
  }
  const std::string table = DistractorSweepMarkdown(sweep);
  EXPECT_THAT(table, HasSubstr("| distortion | method | n | hits, 0 | hits, 1000 |\n"));
  EXPECT_THAT(table, HasSubstr("| gn | product | 4 | 95.0 | 94.0 |\n"));
  EXPECT_THAT(table, Not(HasSubstr("unknown")));
}

TEST(DistractorSweepTest, OnePanelPerDistortion) {
  std::vector<EvaluationReport> one_distortion{Report(0, 200, 30, 190, 34),
                                               Report(1000, 199, 29, 188, 33)};
  for (EvaluationReport& report : one_distortion) report.cells.pop_back();
  const cv::Mat narrow = DrawDistractorSweepPlot(one_distortion);
  const cv::Mat wide =
      DrawDistractorSweepPlot({Report(0, 200, 30, 190, 34), Report(1000, 199, 29, 188, 33)});
  EXPECT_EQ(wide.type(), CV_8UC3);
  EXPECT_EQ(wide.cols, 2 * 460);      // two panels of 460 px side by side
  EXPECT_LT(narrow.cols, wide.cols);  // one panel, widened to fit its legend only
  EXPECT_EQ(narrow.rows, wide.rows);  // one row of panels each
}

TEST(DistractorSweepTest, RefusesReportsThatAreNotOneSweep) {
  EXPECT_THROW(DistractorSweepMarkdown({}), std::invalid_argument);
  EvaluationReport other = Report(1000, 199, 29, 188, 33);
  other.cells.back().distortion = "mb";
  try {
    DistractorSweepMarkdown({Report(0, 200, 30, 190, 34), other});
    FAIL() << "reports of different cells were taken as one sweep";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the reports of 1000 and 0 distractors do not have the same cells");
  }
}

}  // namespace
}  // namespace orbit
