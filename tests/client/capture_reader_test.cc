// Reading a capture (client/capture_reader.h): a generated walk written as an MJPG video and a
// CSV orientation log (evaluation/capture_generator.h) comes back frame by frame with each
// frame's azimuth from the log, the tracked or given region and its quality.
#include "client/capture_reader.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/base/angles.h"
#include "evaluation/capture_generator.h"
#include "tests/support/capture_walks.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ErrorMessageOf;
using testing::ScratchDir;

CaptureGeneratorOptions ShortWalk() { return testing::CoilWalk(7, 24, 120, 12); }

TEST(CaptureReaderTest, ReadsAGeneratedWalkWithAzimuthsFromTheLog) {
  const ScratchDir dir;
  const GeneratedCapture capture = GenerateCapture(ShortWalk());
  WriteCapture(capture, dir / "walk.avi", dir / "walk.csv", dir / "boxes.csv");

  CaptureReader reader((dir / "walk.avi").string(),
                       OrientationLog::ReadFile((dir / "walk.csv").string()),
                       {.first_box = capture.true_boxes[0]});
  EXPECT_DOUBLE_EQ(reader.fps(), 12);
  EXPECT_EQ(reader.frame_count(), 24);
  EXPECT_EQ(reader.frame_size(), cv::Size(320, 240));
  VideoFrame frame;
  long read = 0;
  while (reader.Next(frame)) {
    EXPECT_EQ(frame.index, read);
    EXPECT_DOUBLE_EQ(frame.timestamp_ms, read * 1000.0 / 12);
    // The log: the walk's azimuth, 40 degrees off, 0.4 degrees/s of drift, noise of 3 degrees.
    const double truth = 120.0 * read / 24 + 40 + 0.4 * frame.timestamp_ms / 1000;
    EXPECT_LT(std::abs(AzimuthChange(truth, frame.orientation.azimuth_deg)), 10) << read;
    EXPECT_FALSE(frame.lost);
    EXPECT_GE(IntersectionOverUnion(frame.region, capture.true_boxes[read]), 0.6) << read;
    EXPECT_GT(frame.quality.sharpness, 0);
    ++read;
  }
  EXPECT_EQ(read, 24);

  // Boxes per frame are used as given.
  CaptureReader given((dir / "walk.avi").string(),
                      OrientationLog::ReadFile((dir / "walk.csv").string()),
                      {.boxes = ReadBoxesFile((dir / "boxes.csv").string())});
  for (long f = 0; given.Next(frame); ++f) EXPECT_EQ(frame.region, capture.true_boxes[f]);
}

TEST(CaptureReaderTest, RefusesALogThatEndsBeforeTheVideoAndAMissingVideo) {
  const ScratchDir dir;
  const std::string video = testing::WriteWalk(dir, ShortWalk()).video;
  // 24 frames at 12 fps: the last at 1916.67 ms.
  const std::string log = dir.Write("short.csv", "timestamp_ms,azimuth_deg\n0,0\n1500,90\n");
  EXPECT_EQ(ErrorMessageOf([&] { CaptureReader(video, OrientationLog::ReadFile(log)); }),
            log +
                " does not cover frame 23 (at 1916.67 ms): it covers timestamp_ms 0 to 1500; "
                "a log must span the whole video, from its first frame to its last");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>(
                [&] { CaptureReader((dir / "none.avi").string(), OrientationLog::ReadFile(log)); }),
            "cannot read video " + (dir / "none.avi").string() + ": no such file");
  const std::string text = dir.Write("text.avi", "not a video\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>(
                [&] { CaptureReader(text, OrientationLog::ReadFile(log)); }),
            "cannot read video " + text +
                ": no OpenCV reader opens it (not a video, or a format this OpenCV cannot decode)");
}

TEST(CaptureReaderTest, RefusesAStillImageGivenAsTheVideo) {
  const ScratchDir dir;
  const std::string log = dir.Write("walk.csv", "timestamp_ms,azimuth_deg\n0,0\n1000,90\n");
  // A PNG and a JPEG of the shared data, and the PNG under a video's name: an image states no
  // frame rate, whatever its file is called, so none is read as a one-frame video.
  const std::string png = testing::CoilDir() + "/obj1__0.png";
  const std::string jpeg = (testing::DataDir() / "epfl-cars/images/car01_001.jpg").string();
  std::filesystem::copy_file(png, dir / "walk.avi");
  for (const std::string& image : {png, jpeg, (dir / "walk.avi").string()}) {
    EXPECT_EQ(ErrorMessageOf<std::runtime_error>(
                  [&] { CaptureReader(image, OrientationLog::ReadFile(log)); }),
              "video " + image +
                  " is a still image: it states no frame rate, so no frame time can be aligned "
                  "to the orientation log; give the video of the walk");
  }
}

TEST(CaptureReaderTest, ParsesBoxes) {
  EXPECT_EQ(ParseBox("10,20,30,40"), cv::Rect(10, 20, 30, 40));
  EXPECT_EQ(ErrorMessageOf([] { ParseBox("10,20,0,40"); }),
            "box '10,20,0,40' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)");
  EXPECT_EQ(ErrorMessageOf([] { ParseBox("10,20,30", "--box"); }),
            "--box '10,20,30' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)");
  EXPECT_THROW(ParseBox("10,20,30"), std::invalid_argument);
  EXPECT_THROW(ParseBox("a,20,30,40"), std::invalid_argument);
  EXPECT_THROW(ParseBox("12,40,105066666666666666666666666666660,7"), std::invalid_argument);
  EXPECT_THROW(ParseBox("1048570,0,10,10"), std::invalid_argument);  // past 2^20
  EXPECT_EQ(ParseBox("1048566,0,10,10"), cv::Rect(1048566, 0, 10, 10));
  const ScratchDir dir;
  const std::string boxes = dir.Write("boxes.csv", "frame_index,x,y,w,h\n0,1,2,3,4\n2,1,2,3,4\n");
  EXPECT_EQ(ErrorMessageOf([&] { ReadBoxesFile(boxes); }),
            boxes +
                ":3: expected frame_index 1 (one line per frame, from 0, in order: "
                "frame_index,x,y,w,h)");
}

}  // namespace
}  // namespace orbit
