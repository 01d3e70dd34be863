// The enrollment report as `orbit enroll` and `orbit import` print it.
#include "cli/enrollment_report_text.h"

#include <gtest/gtest.h>

namespace orbit::cli {
namespace {

TEST(EnrollmentReportTextTest, PrintsGapsRepeatsAndConfusableObjects) {
  v1::EnrollmentReport report;
  v1::AzimuthGap* gap = report.add_gaps();
  gap->set_from_deg(300);
  gap->set_to_deg(20);  // across 360: 80 wide
  report.add_redundant_azimuths_deg(90);
  report.add_redundant_azimuths_deg(182.5);
  v1::ConfusableObject* first = report.add_confusable();
  first->set_id(42);
  first->set_name("obj42");
  first->set_similarity(0.9531);
  first->set_closer_views(3);
  v1::ConfusableObject* second = report.add_confusable();
  second->set_id(9);
  second->set_similarity(0.9);
  EXPECT_EQ(EnrollmentReportText(report),
            "  coverage: 1 gap wider than 30 degrees: 300-20 (80)\n"
            "  repeats: 2 views add nothing (at 90, 182.5 degrees)\n"
            "  confusable: obj42 (similarity 0.953, 3 views closer than its own), id 9 "
            "(similarity 0.900)\n");
}

TEST(EnrollmentReportTextTest, SaysWhenCoverageIsComplete) {
  EXPECT_EQ(EnrollmentReportText(v1::EnrollmentReport()),
            "  coverage: no gap wider than 30 degrees\n");
}

}  // namespace
}  // namespace orbit::cli
