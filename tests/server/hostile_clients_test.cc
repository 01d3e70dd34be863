// Hostile clients against a real `orbit serve` (docs/design.md#work-queues,
// docs/design.md#stream-limits): calls abandoned by their callers, a queue flooded with calls,
// a shutdown with work queued, enrollments held open, one token holding every session slot.
// Each attack is made as a client would make it, and each test checks what a well-behaved
// client on the side sees. The idle-connection flood is in connection_admission_test.cc.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <opencv2/imgcodecs.hpp>

#include "core/descriptor/descriptor.h"
#include "orbit/v1/models.grpc.pb.h"
#include "orbit/v1/recognition.grpc.pb.h"
#include "tests/support/http_client.h"
#include "tests/support/metric_sample.h"
#include "tests/support/server_process.h"
#include "tests/support/synthetic_descriptor.h"
#include "tests/support/test_data.h"
#include "tests/support/well_behaved_session.h"

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;
using testing::KeptP99;
using testing::ServerProcess;
using testing::ServerProcessOptions;
using testing::WellBehavedSession;

// A 4096 x 4096 PNG of one grey: about 50 KB on the wire, 48 MiB and a tenth of a second or more
// of a core once decoded. 64 of them fit in one 4 MiB Recognize call.
const std::string& LargePng() {
  static const std::string png = [] {
    std::vector<unsigned char> bytes;
    cv::imencode(".png", cv::Mat(4096, 4096, CV_8UC3, cv::Scalar(90, 120, 150)), bytes);
    return std::string(bytes.begin(), bytes.end());
  }();
  return png;
}

v1::RecognizeRequest ImageBatch(int frames) {
  v1::RecognizeRequest request;
  for (int i = 0; i < frames; ++i) {
    v1::Frame* frame = request.add_frames();
    frame->set_image(LargePng());
    frame->set_azimuth_deg(i);
  }
  return request;
}

// Recognize calls in flight, as a client that sends and forgets (gRPC's callback API: they make
// progress on gRPC's threads while the test does something else).
class PendingCalls {
 public:
  explicit PendingCalls(std::shared_ptr<grpc::Channel> channel)
      : stub_(v1::Recognition::NewStub(std::move(channel))) {}

  void Send(const v1::RecognizeRequest& request, std::chrono::milliseconds deadline,
            const std::string& token = "") {
    calls_.push_back(std::make_unique<Call>());
    Call* call = calls_.back().get();
    call->request = request;
    call->context.set_deadline(std::chrono::system_clock::now() + deadline);
    if (!token.empty()) call->context.AddMetadata("authorization", "Bearer " + token);
    stub_->async()->Recognize(&call->context, &call->request, &call->response,
                              [this, call](grpc::Status status) {
                                std::lock_guard lock(mutex_);
                                call->status = std::move(status);
                                ++ended_;
                                ended_changed_.notify_all();
                              });
  }

  void CancelAll() {
    for (auto& call : calls_) call->context.TryCancel();
  }

  // The status of every call sent, once all have ended.
  std::vector<grpc::Status> Wait() {
    std::unique_lock lock(mutex_);
    ended_changed_.wait(lock, [this] { return ended_ == calls_.size(); });
    std::vector<grpc::Status> statuses;
    for (const auto& call : calls_) statuses.push_back(call->status);
    return statuses;
  }

 private:
  struct Call {
    grpc::ClientContext context;
    v1::RecognizeRequest request;  // outlives the call, as the callback API requires
    v1::RecognizeResponse response;
    grpc::Status status;
  };
  std::unique_ptr<v1::Recognition::Stub> stub_;
  std::vector<std::unique_ptr<Call>> calls_;
  std::mutex mutex_;
  std::condition_variable ended_changed_;
  std::size_t ended_ = 0;
};

int CountCode(const std::vector<grpc::Status>& statuses, grpc::StatusCode code) {
  return static_cast<int>(
      std::count_if(statuses.begin(), statuses.end(),
                    [code](const grpc::Status& s) { return s.error_code() == code; }));
}

// Every status of `code` among `statuses` says `message` (or contains it, when `whole` is false).
void ExpectEveryRefusalSays(const std::vector<grpc::Status>& statuses, grpc::StatusCode code,
                            const std::string& message, bool whole) {
  for (const grpc::Status& status : statuses) {
    if (status.error_code() != code) continue;
    if (whole) {
      EXPECT_EQ(status.error_message(), message);
    } else {
      EXPECT_NE(status.error_message().find(message), std::string::npos) << status.error_message();
    }
  }
}

// A server whose token file grants the recognize role to `first` and `second` (in clear text:
// these tests are about limits, not the file), with `extra_args`.
ServerProcessOptions TwoTokenServer(const testing::ScratchDir& dir, const std::string& first,
                                    const std::string& second,
                                    std::vector<std::string> extra_args) {
  testing::WriteTokenFile(dir / "tokens", first + " recognize\n" + second + " recognize\n");
  ServerProcessOptions options;
  options.tokens_file = dir / "tokens";
  options.extra_args = std::move(extra_args);
  return options;
}

double Metric(const ServerProcess& server, const std::string& series) {
  return testing::Sample(testing::HttpRequest(server.metrics_address(), "GET", "/metrics").body,
                         series);
}

grpc::Status EnrollOne(v1::Models::Stub& models, const std::string& name,
                       std::chrono::seconds deadline) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + deadline);
  v1::ObjectInfo info;
  auto writer = models.Enroll(&context, &info);
  v1::EnrollRequest header;
  header.mutable_header()->set_name(name);
  writer->Write(header);
  for (int v = 0; v < 4; ++v) {
    v1::EnrollRequest view;
    testing::SetDescriptor(*view.mutable_view(), testing::SyntheticDescriptor(v));
    view.mutable_view()->set_azimuth_deg(v * 90.0);
    writer->Write(view);
  }
  writer->WritesDone();
  return writer->Finish();
}

// The review's attack: ten calls of 64 large images each, given up by their caller after half a
// second. Their frames are dropped as soon as the caller has gone (before, the server decoded all
// 640 images, tens of seconds of CPU), and an operator's enrollment is not held behind them.
TEST(HostileClients, AbandonedCallsAreDroppedAndHoldNoOneElseUp) {
  ServerProcessOptions options;
  options.metrics = true;
  options.extra_args = {"--bulk-workers", "1"};
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto models = v1::Models::NewStub(channel);
  WellBehavedSession device(channel);
  const Clock::duration baseline = device.P99(100);

  PendingCalls abandoned(channel);
  for (int i = 0; i < 10; ++i) abandoned.Send(ImageBatch(64), std::chrono::milliseconds(500));
  const Clock::duration under_attack = device.P99(100);
  const grpc::Status enrolled = EnrollOne(*models, "mug", std::chrono::seconds(10));
  EXPECT_TRUE(enrolled.ok()) << enrolled.error_message();
  const std::vector<grpc::Status> statuses = abandoned.Wait();
  EXPECT_EQ(CountCode(statuses, grpc::StatusCode::DEADLINE_EXCEEDED), 10);

  // Every abandoned call is dropped within about a frame of its caller going.
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  while (Metric(server, R"(orbit_worker_queue_depth{pool="bulk_workers"})") > 0 &&
         Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const double image_frames =
      Metric(server, R"(orbit_frame_processing_seconds_count{input="image"})");
  EXPECT_LE(image_frames, 10 * 8) << "of 640 image frames sent";
  EXPECT_GE(Metric(server, R"(orbit_refusals_total{code="CANCELLED",reason="caller_gone"})"), 1);
  EXPECT_LE(under_attack, KeptP99(baseline))
      << "p99 " << testing::Milliseconds(under_attack) << " ms under attack, "
      << testing::Milliseconds(baseline) << " ms before";
  EXPECT_TRUE(device.Close().ok());
}

// More calls than the queue holds: the excess is refused at once, naming the limit, instead of
// holding its request's memory in an unbounded queue; the server serves on.
TEST(HostileClients, CallsBeyondTheQueueAreRefusedAtOnceNamingTheLimit) {
  ServerProcessOptions options;
  options.extra_args = {"--bulk-workers", "1", "--max-queued-calls", "2"};
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  PendingCalls calls(channel);
  for (int i = 0; i < 8; ++i) calls.Send(ImageBatch(64), std::chrono::seconds(60));
  std::this_thread::sleep_for(std::chrono::seconds(2));
  calls.CancelAll();
  const std::vector<grpc::Status> statuses = calls.Wait();
  const int refused = CountCode(statuses, grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_GE(refused, 8 - 1 - 2) << "one running and two queued at most";
  ExpectEveryRefusalSays(statuses, grpc::StatusCode::RESOURCE_EXHAUSTED, "--max-queued-calls 2",
                         false);
  auto models = v1::Models::NewStub(channel);
  EXPECT_TRUE(EnrollOne(*models, "after", std::chrono::seconds(10)).ok());
}

// SIGTERM with image calls queued: the queued ones are answered UNAVAILABLE at once, the running
// one gets --shutdown-grace, and the server exits soon after (before, it ran every queued call
// first, a minute after printing "up to 1 s").
TEST(HostileClients, SigtermAnswersQueuedWorkAndKeepsItsGrace) {
  ServerProcessOptions options;
  options.metrics = true;
  options.extra_args = {"--bulk-workers", "1", "--shutdown-grace", "1"};
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  PendingCalls calls(channel);
  for (int i = 0; i < 6; ++i) calls.Send(ImageBatch(64), std::chrono::seconds(120));
  const auto queued_by = Clock::now() + std::chrono::seconds(20);
  while (Metric(server, R"(orbit_worker_queue_depth{pool="bulk_workers"})") < 5 &&
         Clock::now() < queued_by) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto signalled = Clock::now();
  EXPECT_EQ(server.Stop(SIGTERM, std::chrono::seconds(60)), 0) << server.Log();
  const auto exit_took = Clock::now() - signalled;
  EXPECT_LT(exit_took, std::chrono::seconds(10))
      << std::chrono::duration<double>(exit_took).count() << " s to exit";
  const std::vector<grpc::Status> statuses = calls.Wait();
  EXPECT_GE(CountCode(statuses, grpc::StatusCode::UNAVAILABLE), 5) << "the five queued calls";
}

// Enrollments held open without a message: no more than --max-enrollments at once, each ended
// after --enrollment-idle-timeout, and then an operator enrolls again; a device's session beside
// them keeps its p99.
TEST(HostileClients, HeldEnrollmentsAreCappedAndEndedWhenIdle) {
  ServerProcessOptions options;
  options.extra_args = {"--max-enrollments", "2", "--enrollment-idle-timeout", "2"};
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto models = v1::Models::NewStub(channel);
  WellBehavedSession device(channel);
  const Clock::duration baseline = device.P99(50);
  struct Held {
    grpc::ClientContext context;
    v1::ObjectInfo info;
    std::unique_ptr<grpc::ClientWriter<v1::EnrollRequest>> writer;
  };
  std::vector<std::unique_ptr<Held>> held;
  for (int i = 0; i < 2; ++i) {
    auto stream = std::make_unique<Held>();
    stream->writer = models->Enroll(&stream->context, &stream->info);
    v1::EnrollRequest header;
    header.mutable_header()->set_name("held" + std::to_string(i));
    stream->writer->Write(header);
    held.push_back(std::move(stream));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const grpc::Status third = EnrollOne(*models, "third", std::chrono::seconds(10));
  EXPECT_EQ(third.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << third.error_message();
  EXPECT_NE(third.error_message().find("maximum of 2 enrollments (--max-enrollments)"),
            std::string::npos)
      << third.error_message();
  for (auto& stream : held) {
    const grpc::Status ended = stream->writer->Finish();  // waits for the server to end it
    EXPECT_FALSE(ended.ok());
  }
  // A stream's slot is given back when gRPC ends it on the server, a moment after the client has
  // its status: an operator retrying meanwhile gets RESOURCE_EXHAUSTED, then gets in.
  grpc::Status after = EnrollOne(*models, "after", std::chrono::seconds(10));
  for (int retry = 0; retry < 50 && after.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED;
       ++retry) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    after = EnrollOne(*models, "after", std::chrono::seconds(10));
  }
  EXPECT_TRUE(after.ok()) << after.error_message();
  EXPECT_LE(device.P99(50), KeptP99(baseline));
  EXPECT_TRUE(device.Close().ok());
}

// One token opening sessions until it holds its share is refused beyond it; a device with
// another token still gets a session, and keeps its p99.
TEST(HostileClients, OneTokenCannotHoldEverySessionSlot) {
  testing::ScratchDir dir;
  const std::string hog = "hog-token-0123456789";
  const std::string device_token = "device-token-0123456789";
  ServerProcess server(TwoTokenServer(dir, hog, device_token,
                                      {"--max-sessions", "6", "--max-sessions-per-token", "4"}));
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  WellBehavedSession device(channel, device_token);
  const Clock::duration baseline = device.P99(50);

  std::vector<std::unique_ptr<WellBehavedSession>> hogged;
  for (int i = 0; i < 4; ++i) {
    hogged.push_back(std::make_unique<WellBehavedSession>(channel, hog));
    hogged.back()->P99(1);  // open, and holding its slot
  }
  auto stub = v1::Recognition::NewStub(channel);
  grpc::ClientContext context;
  context.AddMetadata("authorization", "Bearer " + hog);
  auto fifth = stub->Session(&context);
  v1::SessionRequest open;
  open.mutable_open();
  fifth->Write(open);
  fifth->WritesDone();
  const grpc::Status refused = fifth->Finish();
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(refused.error_message().find("(--max-sessions-per-token)"), std::string::npos)
      << refused.error_message();

  WellBehavedSession second_device(channel, device_token);
  EXPECT_LE(second_device.P99(50), KeptP99(baseline));
  EXPECT_TRUE(second_device.Close().ok());
  EXPECT_TRUE(device.Close().ok());
  for (auto& session : hogged) EXPECT_TRUE(session->Close().ok());
}

// One token sending Recognize calls as fast as it can: beyond its share of calls in progress it
// is refused at once, naming the limit, and another token's call is still taken and answered.
TEST(HostileClients, OneTokenCannotFillTheCallQueue) {
  testing::ScratchDir dir;
  const std::string hog = "hog-token-0123456789", device = "device-token-0123456789";
  ServerProcess server(TwoTokenServer(
      dir, hog, device, {"--bulk-workers", "1", "--max-recognize-calls-per-token", "3"}));
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  PendingCalls hogged(channel);
  for (int i = 0; i < 10; ++i) hogged.Send(ImageBatch(4), std::chrono::seconds(60), hog);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  // The device's call, of descriptor frames, is taken and answered while the hog's are in
  // progress.
  PendingCalls fair(channel);
  v1::RecognizeRequest one;
  testing::SetDescriptor(*one.add_frames(), testing::SyntheticDescriptor(1));
  fair.Send(one, std::chrono::seconds(20), device);
  const std::vector<grpc::Status> answered = fair.Wait();
  EXPECT_TRUE(answered[0].ok()) << answered[0].error_message();
  hogged.CancelAll();
  const std::vector<grpc::Status> statuses = hogged.Wait();
  EXPECT_EQ(CountCode(statuses, grpc::StatusCode::RESOURCE_EXHAUSTED), 10 - 3);
  ExpectEveryRefusalSays(
      statuses, grpc::StatusCode::RESOURCE_EXHAUSTED,
      "this token already has 3 calls in progress (--max-recognize-calls-per-token); wait for "
      "one to end",
      true);
}

}  // namespace
}  // namespace orbit
