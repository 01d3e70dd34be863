// SessionReactor (server/session_reactor.h) against a real `orbit serve` process: a device that
// stops reading its updates loses its session slot at the idle timeout instead of holding it.
#include "server/session_reactor.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "orbit/v1/recognition.grpc.pb.h"
#include "tests/support/server_process.h"
#include "tests/support/synthetic_descriptor.h"

namespace orbit {
namespace {

using testing::ServerProcess;

v1::SessionRequest Frame(std::int64_t k) {
  v1::SessionRequest request;
  testing::SetDescriptor(*request.mutable_frame(), testing::UniformDescriptor(1));
  request.mutable_frame()->set_azimuth_deg(static_cast<double>(k % 360));
  return request;
}

TEST(SessionReactorTest, ADeviceThatStopsReadingLosesItsSlotAtTheIdleTimeout) {
  // One session slot, a 1 s idle timeout, and no frame-rate limit in the way.
  testing::ServerProcessOptions options;
  options.extra_args = {"--max-sessions", "1", "--idle-timeout", "1", "--max-fps", "1000000"};
  ServerProcess server(options);

  // The stalled device: its channel lets the server send little before the device must read
  // (no bandwidth probing growing the window), and it never reads.
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  arguments.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 1024);
  auto stalled_channel =
      grpc::CreateCustomChannel(server.address(), grpc::InsecureChannelCredentials(), arguments);
  auto stalled_stub = v1::Recognition::NewStub(stalled_channel);
  grpc::ClientContext stalled_context;
  auto stalled = stalled_stub->Session(&stalled_context);
  std::atomic<std::int64_t> sent{0};
  std::thread writer([&] {
    v1::SessionRequest open;
    open.mutable_open();
    if (!stalled->Write(open)) return;
    // Frames until the server stops taking them (its update writes are stuck behind the
    // device's full window, so it stops reading) or the call ends.
    while (sent < 1000000 && stalled->Write(Frame(sent))) ++sent;
  });

  // Wait until the device's writes stall, then past the idle timeout and a sweep.
  std::int64_t before = -1;
  for (int i = 0; i < 100 && sent.load() != before; ++i) {
    before = sent.load();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_GT(sent.load(), 0);
  ASSERT_LT(sent.load(), 1000000) << "the device's writes never stalled";
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));

  // Another device gets the slot and its answers.
  auto stub = v1::Recognition::NewStub(
      grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  auto session = stub->Session(&context);
  v1::SessionRequest open;
  open.mutable_open();
  ASSERT_TRUE(session->Write(open));
  ASSERT_TRUE(session->Write(Frame(0)));
  v1::SessionUpdate update;
  const bool answered = session->Read(&update);
  session->WritesDone();
  while (session->Read(&update)) {
  }
  const grpc::Status status = session->Finish();
  EXPECT_TRUE(answered) << status.error_code() << ": " << status.error_message();
  EXPECT_TRUE(status.ok()) << status.error_code() << ": " << status.error_message();

  stalled_context.TryCancel();
  writer.join();
  EXPECT_FALSE(stalled->Finish().ok());
}

TEST(SessionReactorTest, ImageFramesNeverDelayAnotherSessionsDescriptorFrames) {
  // One worker for descriptor frames, one for images: three sessions send large (allowed)
  // images, four each, one after another; meanwhile another session streams ten descriptor
  // frames. Its answers must not wait behind the images: it is done while the images are not.
  // (With one shared pool, each of its frames queued behind up to three images, and the image
  // sessions finished first.)
  testing::ServerProcessOptions options;
  options.workers = 1;
  options.extra_args = {"--bulk-workers", "1", "--max-fps", "1000000"};
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto stub = v1::Recognition::NewStub(channel);

  cv::Mat picture(3000, 4000, CV_8UC3, cv::Scalar(40, 90, 160));
  cv::rectangle(picture, {1000, 800, 1500, 1200}, cv::Scalar(200, 30, 30), cv::FILLED);
  std::vector<std::uint8_t> png;
  cv::imencode(".png", picture, png);
  v1::SessionRequest image_frame;
  image_frame.mutable_frame()->set_image(png.data(), png.size());

  constexpr int kImageSessions = 3, kImagesEach = 4, kDescriptorFrames = 10;
  std::atomic<int> image_updates{0};
  std::atomic<int> image_sessions_open{0};
  std::vector<std::thread> image_sessions;
  for (int s = 0; s < kImageSessions; ++s) {
    image_sessions.emplace_back([&] {
      grpc::ClientContext context;
      auto stream = stub->Session(&context);
      v1::SessionRequest open;
      open.mutable_open();
      stream->Write(open);
      ++image_sessions_open;
      v1::SessionUpdate update;
      for (int k = 0; k < kImagesEach && stream->Write(image_frame) && stream->Read(&update); ++k) {
        ++image_updates;
      }
      stream->WritesDone();
      EXPECT_TRUE(stream->Finish().ok());
    });
  }
  while (image_sessions_open.load() < kImageSessions) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the images are being decoded

  grpc::ClientContext context;
  auto session = stub->Session(&context);
  v1::SessionRequest open;
  open.mutable_open();
  ASSERT_TRUE(session->Write(open));
  v1::SessionUpdate update;
  int answered = 0;
  for (int k = 0; k < kDescriptorFrames && session->Write(Frame(k)) && session->Read(&update);
       ++k) {
    ++answered;
  }
  const int images_done_meanwhile = image_updates.load();
  session->WritesDone();
  EXPECT_TRUE(session->Finish().ok());
  for (std::thread& t : image_sessions) t.join();

  EXPECT_EQ(answered, kDescriptorFrames);
  EXPECT_EQ(image_updates.load(), kImageSessions * kImagesEach);
  EXPECT_LT(images_done_meanwhile, kImageSessions * kImagesEach)
      << "the descriptor frames were answered only after every image";
}

}  // namespace
}  // namespace orbit
