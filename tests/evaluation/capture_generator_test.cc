// Generated captures (evaluation/capture_generator.h): deterministic, the object's true box
// inside every frame, the blurred and noisy frames where they are said to be, and a log that
// covers the video and reads the walk's azimuth with the stated offset, drift and noise.
#include "evaluation/capture_generator.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "client/frame_quality.h"
#include "core/base/angles.h"
#include "tests/support/capture_walks.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

CaptureGeneratorOptions Walk() { return testing::CoilWalk(4, 30, 150); }

TEST(CaptureGeneratorTest, RendersAKnownWalk) {
  const GeneratedCapture capture = GenerateCapture(Walk());
  ASSERT_EQ(capture.frames.size(), 30u);
  const cv::Rect frame(0, 0, 320, 240);
  for (std::size_t f = 0; f < capture.frames.size(); ++f) {
    EXPECT_EQ(capture.frames[f].size(), frame.size());
    EXPECT_EQ(capture.true_boxes[f] & frame, capture.true_boxes[f]);
    EXPECT_GT(capture.true_boxes[f].area(), 60 * 60);
    EXPECT_EQ(capture.shown_azimuths[f], 5 * static_cast<int>(f));  // 150 degrees in 30 frames
    // Every 9th frame blurred, every 13th noisy.
    EXPECT_EQ(capture.degraded[f], f % 9 == 8 || f % 13 == 12) << f;
  }
  // A blurred frame is far less sharp than its neighbour, a noisy one far noisier.
  const FrameQuality sharp = MeasureFrameQuality(capture.frames[7], capture.true_boxes[7]);
  const FrameQuality blurred = MeasureFrameQuality(capture.frames[8], capture.true_boxes[8]);
  const FrameQuality noisy = MeasureFrameQuality(capture.frames[12], capture.true_boxes[12]);
  EXPECT_LT(blurred.sharpness, 0.35 * sharp.sharpness);
  EXPECT_LT(sharp.noise_sigma, 6);
  EXPECT_GT(noisy.noise_sigma, 12);

  // The log: from 0 past the last frame (2.9 s), 27 readings a second, each the walk's azimuth
  // plus 40 degrees, 0.4 degrees/s of drift and noise of 3 degrees.
  ASSERT_GE(capture.log.size(), 78u);
  EXPECT_EQ(capture.log.front().time, 0);
  EXPECT_GT(capture.log.back().time, 2900);
  double squares = 0;
  for (const OrientationReading& r : capture.log) {
    const double truth = 150.0 * (r.time / 1000 * 10) / 30 + 40 + 0.4 * r.time / 1000;
    const double error = AzimuthChange(truth, r.azimuth_deg);
    squares += error * error;
  }
  const double deviation = std::sqrt(squares / capture.log.size());
  EXPECT_GT(deviation, 2.4);
  EXPECT_LT(deviation, 3.6);

  // Deterministic.
  const GeneratedCapture again = GenerateCapture(Walk());
  EXPECT_EQ(cv::norm(again.frames[13], capture.frames[13], cv::NORM_INF), 0);
  EXPECT_EQ(again.log[5].azimuth_deg, capture.log[5].azimuth_deg);
}

TEST(CaptureGeneratorTest, WritesAVideoAnyOpenCvReadsBack) {
  const testing::ScratchDir dir;
  const GeneratedCapture capture = GenerateCapture(Walk());
  WriteCapture(capture, dir / "walk.avi", dir / "walk.csv", dir / "boxes.csv");
  cv::VideoCapture video((dir / "walk.avi").string());
  ASSERT_TRUE(video.isOpened());
  EXPECT_DOUBLE_EQ(video.get(cv::CAP_PROP_FPS), 10);
  cv::Mat frame;
  int frames = 0;
  while (video.read(frame)) {
    // Motion-JPEG: close to the rendered frame, not equal; it smooths away much of the noise of
    // the noisy frames, which stay further from theirs.
    const double difference = cv::norm(frame, capture.frames[frames], cv::NORM_L1) / frame.total();
    EXPECT_LT(difference, capture.degraded[frames] ? 60 : 20) << frames;
    ++frames;
  }
  EXPECT_EQ(frames, 30);
  EXPECT_THROW(WriteCapture(capture, dir / "no" / "walk.avi", dir / "walk.csv"),
               std::runtime_error);
}

}  // namespace
}  // namespace orbit
