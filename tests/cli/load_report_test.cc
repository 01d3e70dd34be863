#include "cli/load_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace orbit {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// 300 frames answered in 10 s: round trips of 1, 2 and 3 ms (100 each), the server busy 1.5 s
// and the generator 0.6 s meanwhile; two sessions refused.
LoadReport ARun() {
  LoadReport report;
  report.server = "127.0.0.1:50051";
  report.engine = "hmm";
  report.sessions = 6;
  report.rate = 5;
  report.duration_seconds = 10;
  report.elapsed_seconds = 10;
  report.sessions_opened = 4;
  report.sessions_failed = 2;
  report.frames_sent = 300;
  report.frames_answered = 300;
  for (int ms = 1; ms <= 3; ++ms) {
    for (int i = 0; i < 100; ++i) {
      report.round_trip.Record(ms * 1000);
      report.processing.Record(ms * 100);
    }
  }
  report.errors["RESOURCE_EXHAUSTED"] = 2;
  report.server_start = ProcessUsage{1.0, 50 << 20};
  report.server_end = ProcessUsage{2.5, 60 << 20};
  report.generator_cpu_seconds = 0.6;
  return report;
}

TEST(LoadReportTest, JsonHasThroughputRoundTripsErrorsAndCpuPerFrame) {
  const nlohmann::ordered_json json = LoadReportJson(ARun());
  EXPECT_EQ(json["frames_per_second"], 30.0);
  // Percentiles are the middles of their buckets, to the microsecond: rank 150 of 300 is
  // 2000 us, in [2000, 2015] (middle 2007.5); ranks 270 and 297 are 3000 us, in [2976, 3007]
  // (middle 2991.5). The max is exact.
  EXPECT_EQ(json["rtt_ms"]["p50"], 2.008);
  EXPECT_EQ(json["rtt_ms"]["p90"], 2.992);
  EXPECT_EQ(json["rtt_ms"]["p99"], 2.992);
  EXPECT_EQ(json["rtt_ms"]["max"], 3.0);
  EXPECT_EQ(json["rtt_ms"]["mean"], 2.0);
  EXPECT_EQ(json["errors"], (nlohmann::ordered_json{{"RESOURCE_EXHAUSTED", 2}}));
  EXPECT_EQ(json["sessions"]["asked"], 6);
  EXPECT_EQ(json["sessions"]["opened"], 4);
  EXPECT_EQ(json["sessions"]["failed"], 2);
  EXPECT_EQ(json["frames"]["unanswered"], 0);
  // 200 us is in [200, 201] (middle 200.5, rounded up); 300 us in [300, 303], its middle
  // clamped to the max.
  EXPECT_EQ(json["server"]["processing_time_us"]["p50"], 201);
  EXPECT_EQ(json["server"]["processing_time_us"]["p99"], 300);
  // 1.5 s of server CPU over 300 frames is 5000 us a frame, 15% of a core over 10 s.
  EXPECT_EQ(json["server"]["cpu_us_per_frame"], 5000.0);
  EXPECT_EQ(json["server"]["cpu_percent"], 15.0);
  EXPECT_EQ(json["server"]["rss_mb_start"], 50.0);
  EXPECT_EQ(json["server"]["rss_mb_end"], 60.0);
  EXPECT_EQ(json["generator"]["cpu_us_per_frame"], 2000.0);
  EXPECT_EQ(json["generator"]["cpu_percent"], 6.0);
  EXPECT_EQ(json["config"]["mode"], "open-loop");
  EXPECT_EQ(json["config"]["rate_per_session"], 5.0);
  EXPECT_FALSE(json.contains("enrollments"));
}

TEST(LoadReportTest, WithoutAServerPidOrErrorsThoseFiguresAreLeftOut) {
  LoadReport report = ARun();
  report.server_start.reset();
  report.server_end.reset();
  report.errors.clear();
  report.rate.reset();
  const nlohmann::ordered_json json = LoadReportJson(report);
  EXPECT_TRUE(json["errors"].is_object());
  EXPECT_TRUE(json["errors"].empty());
  EXPECT_FALSE(json["server"].contains("cpu_us_per_frame"));
  EXPECT_EQ(json["config"]["mode"], "closed-loop");
  EXPECT_FALSE(json["config"].contains("rate_per_session"));
  const std::string text = LoadReportText(report);
  EXPECT_THAT(text, HasSubstr("errors       none"));
  EXPECT_THAT(text, HasSubstr("(closed loop)"));
  EXPECT_THAT(text, Not(HasSubstr("RSS")));
}

TEST(LoadReportTest, TextSaysWhatTheRunMeasured) {
  LoadReport report = ARun();
  report.enrollments_run = true;
  report.enrollments_done = 2;
  report.enrollments_deleted = 2;
  report.enrollment_views = 72;
  report.enrollment.Record(250000);
  report.round_trip_enrolling.Record(5000);
  const std::string text = LoadReportText(report);
  EXPECT_THAT(text, HasSubstr("6 sessions x 5 frames/s (open loop), hmm, descriptor frames"));
  EXPECT_THAT(text, HasSubstr("300 sent, 300 answered in 10.00 s: 30.0 frames/s"));
  EXPECT_THAT(text, HasSubstr("p50 2.008  p90 2.992  p99 2.992  max 3.000 ms"));
  EXPECT_THAT(text, HasSubstr("4 opened, 2 failed"));
  EXPECT_THAT(text, HasSubstr("RESOURCE_EXHAUSTED 2"));
  EXPECT_THAT(text,
              HasSubstr("CPU 1.50 s = 5000.0 us/frame (15.0% of a core); RSS 50.0 -> 60.0 MB"));
  EXPECT_THAT(text, HasSubstr("generator    CPU 0.60 s = 2000.0 us/frame (6.0% of a core)"));
  EXPECT_THAT(text, HasSubstr("enrollments  2 of 72 views each"));
  const nlohmann::ordered_json json = LoadReportJson(report);
  EXPECT_EQ(json["enrollments"]["done"], 2);
  EXPECT_EQ(json["enrollments"]["latency_ms"]["max"], 250.0);
  EXPECT_EQ(json["enrollments"]["rtt_ms_during"]["count"], 1);
}

}  // namespace
}  // namespace orbit
