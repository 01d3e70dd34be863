// SessionReactor (server/session_reactor.h) against a real `orbit serve` process: a device that
// stops reading its updates loses its session slot at the idle timeout instead of holding it.
#include "server/session_reactor.h"

#include <atomic>
#include <chrono>
#include <thread>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "orbit/v1/recognition.grpc.pb.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::ServerProcess;

v1::SessionRequest Frame(std::int64_t k) {
  v1::SessionRequest request;
  request.mutable_frame()->set_cedd(std::string(kDescriptorSize, '\1'));
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

}  // namespace
}  // namespace orbit
