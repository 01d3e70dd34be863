// What `orbit enroll --video` says about the views it took (cli/capture_selection_text.cc), on a
// walk made by hand from COIL-100 views so that every frame's azimuth and fate is known: a real
// video and orientation log, enrolled on a real `orbit serve` process.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "client/image_file.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilFile;
using testing::OutputLines;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::ServerProcess;

TEST(CaptureSelectionTextTest, NamesTheFrameOfEveryStepWhyAStepHasNoneAndTheArcsToWalkAgain) {
  const ScratchDir dir;
  // Seven frames of object 3, each in its own step of 25 degrees, with the log's azimuth: steps
  // 0, 1, 3 and 6, 7 get a clean view; step 4 only a blurred one, step 5 only a noisy one; step
  // 2 and everything from 200 degrees on no frame at all.
  const std::vector<std::pair<int, double>> walk = {{0, 5},     {40, 40},   {85, 83},  {110, 110},
                                                    {135, 135}, {160, 160}, {180, 185}};
  cv::VideoWriter video((dir / "walk.avi").string(), cv::CAP_FFMPEG,
                        cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(128, 128));
  ASSERT_TRUE(video.isOpened());
  std::string log = "frame_index,azimuth_deg\n";
  for (std::size_t f = 0; f < walk.size(); ++f) {
    cv::Mat frame = ReadImageFile(CoilFile(3, walk[f].first));
    if (f == 3) cv::GaussianBlur(frame, frame, cv::Size(), 6);
    if (f == 4) {
      cv::Mat noise(frame.size(), CV_16SC3);
      cv::randn(noise, 0, 40);
      cv::Mat noisy;
      frame.convertTo(noisy, CV_16SC3);
      cv::Mat(noisy + noise).convertTo(frame, CV_8UC3);
    }
    video.write(frame);
    log += std::to_string(f) + "," + std::to_string(walk[f].second) + "\n";
  }
  video.release();
  dir.Write("walk.csv", log);

  ServerProcess server;
  const testing::CommandResult enrolled =
      RunOrbit("enroll --server " + server.address() + " --name obj3 --step 25 --video " +
               (dir / "walk.avi").string() + " --orientation " + (dir / "walk.csv").string());
  ASSERT_EQ(enrolled.exit_code, 0) << enrolled.err;
  const std::vector<std::string> lines = OutputLines(enrolled.out);
  ASSERT_GE(lines.size(), 19u) << enrolled.out;
  const std::vector<std::string> expected = {
      "enrolled obj3 (id 1, 5 views)",
      "  capture: 7 frames, 0 lost, 2 too blurred or noisy; views in 5 of 15 steps of 25 degrees",
      "  step 0-25: frame 0 at 5.0 degrees",
      "  step 25-50: frame 1 at 40.0 degrees",
      "  step 50-75: no view: no frame (the walk did not pass here)",
      "  step 75-100: frame 2 at 83.0 degrees",
      "  step 100-125: no view: 1 frame, too blurred",
      "  step 125-150: no view: 1 frame, too noisy",
      "  step 150-175: frame 5 at 160.0 degrees",
      "  step 175-200: frame 6 at 185.0 degrees",
      "  step 200-225: no view: no frame (the walk did not pass here)",
      "  step 225-250: no view: no frame (the walk did not pass here)",
      "  step 250-275: no view: no frame (the walk did not pass here)",
      "  step 275-300: no view: no frame (the walk did not pass here)",
      "  step 300-325: no view: no frame (the walk did not pass here)",
      "  step 325-350: no view: no frame (the walk did not pass here)",
      "  step 350-360: no view: no frame (the walk did not pass here)",
      // Steps 0 and 1 both have a view, yet 35 degrees lie between them; 160 -> 185 is no
      // wider than the step.
      "  gaps: 4 arcs between views wider than the step of 25 degrees: 5.0-40.0 (35.0), "
      "40.0-83.0 (43.0), 83.0-160.0 (77.0), 185.0-5.0 (180.0): walk those arcs again slowly, "
      "keeping the object in the box, or give a smaller --step",
  };
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(lines[i], expected[i]) << i;
  // The server's report follows.
  EXPECT_EQ(lines[expected.size()].rfind("  coverage: ", 0), 0u) << enrolled.out;
}

}  // namespace
}  // namespace orbit
