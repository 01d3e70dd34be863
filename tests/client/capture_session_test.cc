// A recognition session fed by a capture (client/capture_session.h) against a real server:
// every tracked frame sent with its azimuth, region, time and quality, lost frames not sent.
#include "client/capture_session.h"

#include <gtest/gtest.h>

#include "evaluation/capture_generator.h"
#include "tests/support/capture_walks.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

TEST(CaptureSessionTest, StreamsEveryFoundFrameAndSkipsLostOnes) {
  const testing::ScratchDir dir;
  const testing::WrittenWalk walk = testing::WriteWalk(dir, testing::CoilWalk(2, 16, 80, 8));

  testing::ServerProcess server;
  const Connection connection(testing::At(server.address()));
  testing::EnrollCoilObjects(connection, 1, 3);  // every 10 degrees, on black

  // The true boxes; the first four frames' boxes outside the frame: lost, not sent.
  std::vector<cv::Rect> boxes = walk.capture.true_boxes;
  for (int f = 0; f < 4; ++f) boxes[f] = cv::Rect(400, 300, 20, 20);
  CaptureReader reader(walk.video, OrientationLog::ReadFile(walk.log), {.boxes = boxes});
  auto session = RecognitionSession::Open(connection, testing::TopK(3));
  long progress = 0;
  const CaptureStreamResult streamed =
      StreamCapture(*session, reader, {.real_time = false, .progress = [&](long read, long total) {
                                         EXPECT_EQ(total, 16);
                                         progress = read;
                                       }});
  EXPECT_EQ(progress, 16);
  EXPECT_EQ(streamed.frames_read, 16);
  EXPECT_EQ(streamed.frames_sent, 12);
  EXPECT_EQ(streamed.frames_lost, 4);
  ASSERT_TRUE(session->Close().ok());

  int updates = 0;
  int right = 0;
  while (const std::optional<v1::SessionUpdate> update = session->NextUpdate()) {
    // Frame times are echoed: the first sent frame is the video's 5th, at 4/8 s.
    EXPECT_EQ(update->timestamp_us(), (4 + updates) * 125000) << updates;
    ASSERT_GT(update->candidates_size(), 0);
    right += update->candidates(0).name() == "obj2" ? 1 : 0;
    ++updates;
  }
  EXPECT_EQ(updates, 12);
  // Object 2 from a cluttered walk against views taken on black.
  EXPECT_GE(right, 10);
}

}  // namespace
}  // namespace orbit
