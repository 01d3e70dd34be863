// Orientation logs (client/orientation_log.h): parsing, validation with messages naming the
// file and line, and the azimuth each frame gets, across 0/360 and across gaps.
#include "client/orientation_log.h"

#include <sstream>

#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ErrorMessageOf;

OrientationLog Parse(const std::string& text) {
  std::istringstream in(text);
  return OrientationLog::Parse(in, "walk.csv");
}

TEST(OrientationLogTest, InterpolatesOnTheShorterArcAcrossZero) {
  const OrientationLog log = Parse("timestamp_ms,azimuth_deg\n0,350\n100,10\n200,-20\n");
  EXPECT_EQ(log.clock(), OrientationClock::kTimestampMs);
  ASSERT_EQ(log.readings().size(), 3u);
  EXPECT_DOUBLE_EQ(log.At(0, 0).azimuth_deg, 350);
  EXPECT_NEAR(log.At(1, 25).azimuth_deg, 355, 1e-9);
  EXPECT_NEAR(log.At(2, 50).azimuth_deg, 0, 1e-9);  // not 180, the long way round
  EXPECT_NEAR(log.At(3, 75).azimuth_deg, 5, 1e-9);
  EXPECT_DOUBLE_EQ(log.At(4, 100).azimuth_deg, 10);
  // 10 to -20 (340): 30 degrees back, through 0 again; results are in [0, 360).
  EXPECT_NEAR(log.At(5, 150).azimuth_deg, 355, 1e-9);
  EXPECT_DOUBLE_EQ(log.At(6, 200).azimuth_deg, 340);
  EXPECT_FALSE(log.At(6, 200).elevation_deg.has_value());
}

TEST(OrientationLogTest, InterpolatesAcrossAGapAndAlignsAnyRate) {
  // 50 Hz, then a 900 ms gap in the readings, then 50 Hz again; the video's frames at 30 fps
  // fall between readings.
  const OrientationLog log = Parse(
      "# compass of the walk\n"
      "timestamp_ms,azimuth_deg,elevation_deg\n"
      "0,100,10\n20,102,10\n\n100,110,12\n1000,200,30\n1020,202,30\n");
  // 1/30 s: a sixth of the way from 20 ms (102) to 100 ms (110).
  EXPECT_NEAR(log.At(1, 1000.0 / 30).azimuth_deg, 102 + 8.0 / 6, 1e-9);
  const FrameOrientation in_gap = log.At(16, 550);
  EXPECT_NEAR(in_gap.azimuth_deg, 155, 1e-9);
  ASSERT_TRUE(in_gap.elevation_deg.has_value());
  EXPECT_NEAR(*in_gap.elevation_deg, 21, 1e-9);
  EXPECT_NEAR(log.At(30, 1010).azimuth_deg, 201, 1e-9);
}

TEST(OrientationLogTest, FrameIndexLogsGiveEachFrameItsOwnReading) {
  const OrientationLog log = Parse("frame_index,azimuth_deg\n0,359\n1,1\n2,4\n4,8\n");
  EXPECT_EQ(log.clock(), OrientationClock::kFrameIndex);
  // The timestamp is ignored: frames are matched by index.
  EXPECT_DOUBLE_EQ(log.At(1, 12345).azimuth_deg, 1);
  EXPECT_DOUBLE_EQ(log.At(3, 0).azimuth_deg, 6);  // frame 3 missing: between its neighbours
  EXPECT_NO_THROW(log.RequireCovers(5, 999));
  EXPECT_EQ(ErrorMessageOf([&] { log.RequireCovers(6, 999); }),
            "walk.csv does not cover frame 5 (at 999 ms): it covers frame_index 0 to 4; a log "
            "must span the whole video, from its first frame to its last");
}

TEST(OrientationLogTest, AFileWithoutHeaderIsReadAsTimestamps) {
  const OrientationLog log = Parse("0,10\n500,20\n");
  EXPECT_EQ(log.clock(), OrientationClock::kTimestampMs);
  EXPECT_DOUBLE_EQ(log.At(7, 250).azimuth_deg, 15);
}

TEST(OrientationLogTest, RefusesALogThatDoesNotCoverTheVideo) {
  const OrientationLog log = Parse("timestamp_ms,azimuth_deg\n40,0\n1000,90\n");
  EXPECT_EQ(ErrorMessageOf([&] { log.RequireCovers(31, 1000); }),
            "walk.csv does not cover frame 0 (at 0 ms): it covers timestamp_ms 40 to 1000; a "
            "log must span the whole video, from its first frame to its last");
  const OrientationLog short_log = Parse("timestamp_ms,azimuth_deg\n0,0\n900,90\n");
  EXPECT_EQ(ErrorMessageOf([&] { short_log.RequireCovers(31, 1000); }),
            "walk.csv does not cover frame 30 (at 1000 ms): it covers timestamp_ms 0 to 900; a "
            "log must span the whole video, from its first frame to its last");
  EXPECT_THROW(short_log.At(1, 900.5), std::invalid_argument);
}

TEST(OrientationLogTest, RefusesBadLinesNamingFileAndLine) {
  EXPECT_EQ(ErrorMessageOf([] { Parse("timestamp_ms,azimuth_deg\n0,1\n50,2\n40,3\n"); }),
            "walk.csv:4: timestamp_ms 40 goes backwards in time: it must be greater than the "
            "previous reading's 50");
  EXPECT_EQ(ErrorMessageOf([] { Parse("timestamp_ms,azimuth_deg\n0,1\n50,2\n50,3\n"); }),
            "walk.csv:4: timestamp_ms 50 goes backwards in time: it must be greater than the "
            "previous reading's 50");
  EXPECT_EQ(ErrorMessageOf([] { Parse("timestamp_ms,azimuth_deg\n0,1\n50,nan\n"); }),
            "walk.csv:3: values must be finite numbers");
  EXPECT_EQ(ErrorMessageOf([] { Parse("0,1\n50,inf\n"); }),
            "walk.csv:2: values must be finite numbers");
  EXPECT_EQ(ErrorMessageOf([] { Parse("0,1,95\n"); }),
            "walk.csv:1: elevation_deg 95 is outside [-90, 90]");
  EXPECT_EQ(ErrorMessageOf([] { Parse("0,north\n"); }), "walk.csv:1: 'north' is not a number");
  EXPECT_EQ(ErrorMessageOf([] { Parse("0,1\n10,2,3,4\n"); }),
            "walk.csv:2: expected 2 or 3 values (timestamp_ms,azimuth_deg[,elevation_deg]), "
            "got 4");
  EXPECT_EQ(ErrorMessageOf([] { Parse("-5,1\n"); }),
            "walk.csv:1: timestamp_ms -5 is outside [0, 1e12]; it counts from the video's first "
            "frame (0)");
  EXPECT_EQ(ErrorMessageOf([] { Parse("frame_index,azimuth_deg\n0,1\n2e12,2\n"); }),
            "walk.csv:3: frame_index 2e+12 is outside [0, 1e12]; it counts from the video's "
            "first frame (0)");
  EXPECT_EQ(ErrorMessageOf([] { Parse("frame_index,azimuth_deg\n0.5,1\n"); }),
            "walk.csv:2: frame_index 0.5 is not a whole number");
  EXPECT_EQ(ErrorMessageOf([] { Parse("time,heading\n0,1\n"); }),
            "walk.csv:1: unknown header 'time,heading': expected "
            "timestamp_ms,azimuth_deg[,elevation_deg] or frame_index,azimuth_deg[,elevation_deg]");
  EXPECT_EQ(ErrorMessageOf([] { Parse("# nothing\n\n"); }),
            "walk.csv: no orientation readings (lines timestamp_ms,azimuth_deg[,elevation_deg])");
  EXPECT_EQ(
      ErrorMessageOf<std::runtime_error>([] { OrientationLog::ReadFile("/nonexistent/walk.csv"); }),
      "cannot read orientation log /nonexistent/walk.csv");
}

}  // namespace
}  // namespace orbit
