// The server's metrics (server/server_metrics.h): what a fresh ServerMetrics exposes, and a real
// `orbit serve --metrics-listen` scraped over HTTP before and after a session, an enrollment and
// refused requests, checking that each counter moved by exactly what was done.
#include "server/server_metrics.h"

#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "orbit/v1/models.grpc.pb.h"
#include "orbit/v1/recognition.grpc.pb.h"
#include "server/metrics_endpoint.h"
#include "tests/support/http_client.h"
#include "tests/support/metric_sample.h"
#include "tests/support/server_process.h"
#include "tests/support/synthetic_descriptor.h"
#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

using ::testing::HasSubstr;
using testing::HttpRequest;
using testing::Sample;

const std::string kInvalidField =
    R"(orbit_refusals_total{code="INVALID_ARGUMENT",reason="invalid_field"})";

TEST(ServerMetricsTest, EveryMetricIsExposedFromTheStartWithItsChildrenAtZero) {
  ServerMetrics metrics;
  const std::string text = metrics.Expose();
  for (const char* family :
       {"orbit_frames_processed_total counter", "orbit_frame_processing_seconds histogram",
        "orbit_refusals_total counter", "orbit_enrollments_total counter",
        "orbit_enrollment_seconds histogram", "orbit_store_write_seconds histogram",
        "orbit_model_change_lag_seconds histogram"}) {
    EXPECT_THAT(text, HasSubstr(std::string("# TYPE ") + family + "\n"));
  }
  for (const char* engine : {"vci", "hmm", "vci-hmm", "vci-bm", "vci-w0", "eis", "siis", "eiis"}) {
    EXPECT_EQ(Sample(text, std::string("orbit_frames_processed_total{engine=\"") + engine + "\"}"),
              0);
  }
  EXPECT_EQ(Sample(text, kInvalidField), 0);
  EXPECT_EQ(Sample(text, R"(orbit_refusals_total{code="RESOURCE_EXHAUSTED",reason="frame_rate"})"),
            0);
  EXPECT_EQ(Sample(text, R"(orbit_refusals_total{code="DEADLINE_EXCEEDED",reason="idle_timeout"})"),
            0);
  for (const char* outcome : {"stored", "refused", "failed", "cancelled"}) {
    EXPECT_EQ(Sample(text, std::string("orbit_enrollments_total{outcome=\"") + outcome + "\"}"), 0);
  }
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="cedd",le="1e-05"})"), 0);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_count{input="image"})"), 0);
  EXPECT_EQ(Sample(text, R"(orbit_store_write_seconds_count{operation="delete"})"), 0);
  EXPECT_EQ(Sample(text, "orbit_enrollment_seconds_count"), 0);
  EXPECT_EQ(Sample(text, "orbit_model_change_lag_seconds_count"), 0);
  // Gauges appear once the server gives them something to watch.
  EXPECT_THAT(text, ::testing::Not(HasSubstr("orbit_open_sessions")));
}

TEST(ServerMetricsTest, AFrameCountsForItsEngineAndItsInput) {
  ServerMetrics metrics;
  const FrameMetrics hmm = metrics.ForEngine(v1::ENGINE_HMM);
  hmm.Record(FrameInput::kCedd, std::chrono::microseconds(20));  // bucket le=2.5e-05
  hmm.Record(FrameInput::kCedd, std::chrono::microseconds(30));  // le=5e-05
  metrics.ForEngine(v1::ENGINE_VCI).Record(FrameInput::kImage, std::chrono::milliseconds(3));
  const std::string text = metrics.Expose();
  EXPECT_EQ(Sample(text, R"(orbit_frames_processed_total{engine="hmm"})"), 2);
  EXPECT_EQ(Sample(text, R"(orbit_frames_processed_total{engine="vci"})"), 1);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="cedd",le="1e-05"})"), 0);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="cedd",le="2.5e-05"})"), 1);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="cedd",le="5e-05"})"), 2);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_count{input="cedd"})"), 2);
  EXPECT_DOUBLE_EQ(Sample(text, R"(orbit_frame_processing_seconds_sum{input="cedd"})"), 5e-5);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="image",le="0.0025"})"), 0);
  EXPECT_EQ(Sample(text, R"(orbit_frame_processing_seconds_bucket{input="image",le="0.005"})"), 1);
  // A value outside the proto's engines is still counted, apart.
  metrics.ForEngine(static_cast<v1::Engine>(99)).Record(FrameInput::kCedd, {});
  EXPECT_EQ(Sample(metrics.Expose(), R"(orbit_frames_processed_total{engine="unknown"})"), 1);
}

TEST(ServerMetricsTest, RefuseCountsByCodeAndReasonAndPassesTheStatusOn) {
  ServerMetrics metrics;
  const grpc::Status refused =
      metrics.Refuse({grpc::StatusCode::RESOURCE_EXHAUSTED, "more than 60 frames per second"},
                     RefusalReason::kFrameRate);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(refused.error_message(), "more than 60 frames per second");
  EXPECT_TRUE(metrics.Refuse(grpc::Status::OK, RefusalReason::kInternal).ok());  // not counted
  metrics.CountRefusal(grpc::StatusCode::ABORTED, RefusalReason::kStore);  // outside kRefusalKinds
  const std::string text = metrics.Expose();
  EXPECT_EQ(Sample(text, R"(orbit_refusals_total{code="RESOURCE_EXHAUSTED",reason="frame_rate"})"),
            1);
  EXPECT_EQ(Sample(text, R"(orbit_refusals_total{code="ABORTED",reason="store"})"), 1);
  EXPECT_EQ(Sample(text, R"(orbit_refusals_total{code="INTERNAL",reason="internal"})"), 0);
  EXPECT_THAT(text, ::testing::Not(HasSubstr("code=\"OK\"")));
}

// ---- a real server, scraped ----

DescriptorValues Descriptor(int seed) { return testing::SyntheticDescriptor(seed); }

std::string Scrape(const std::string& address) {
  const testing::HttpResponse response = HttpRequest(address, "GET", "/metrics");
  EXPECT_EQ(response.status, 200);
  EXPECT_THAT(response.headers.at("content-type"), HasSubstr("text/plain"));
  return response.body;
}

// Scrapes until `series` reads `value` (it may lag the client by a moment: a stream's slot is
// freed when gRPC calls OnDone, after the client has its status); at most 10 s.
double ScrapeUntil(const std::string& address, const std::string& series, double value) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  double seen = Sample(Scrape(address), series);
  while (seen != value && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    seen = Sample(Scrape(address), series);
  }
  return seen;
}

grpc::Status Enroll(v1::Models::Stub& models, const std::string& name, int views) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  v1::ObjectInfo info;
  auto writer = models.Enroll(&context, &info);
  v1::EnrollRequest header;
  header.mutable_header()->set_name(name);
  writer->Write(header);
  for (int v = 0; v < views; ++v) {
    v1::EnrollRequest view;
    testing::SetDescriptor(*view.mutable_view(), Descriptor(v));
    view.mutable_view()->set_azimuth_deg(v * 30.0);
    writer->Write(view);
  }
  writer->WritesDone();
  return writer->Finish();
}

v1::SessionRequest Frame(const DescriptorValues& descriptor, double azimuth) {
  v1::SessionRequest request;
  testing::SetDescriptor(*request.mutable_frame(), descriptor);
  request.mutable_frame()->set_azimuth_deg(azimuth);
  return request;
}

TEST(ServerMetricsTest, ARealServerCountsWhatItDid) {
  testing::ServerProcess server({.metrics = true});
  const std::string metrics = server.metrics_address();
  ASSERT_FALSE(metrics.empty()) << server.Log();
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto models = v1::Models::NewStub(channel);
  auto recognition = v1::Recognition::NewStub(channel);

  const std::string before = Scrape(metrics);
  EXPECT_EQ(Sample(before, "orbit_open_sessions"), 0);
  EXPECT_EQ(Sample(before, "orbit_index_objects"), 0);
  EXPECT_EQ(Sample(before, "orbit_index_views"), 0);
  EXPECT_EQ(Sample(before, R"(orbit_worker_queue_depth{pool="workers"})"), 0);
  EXPECT_EQ(Sample(before, R"(orbit_worker_queue_depth{pool="bulk_workers"})"), 0);
  const std::string hmm_frames = R"(orbit_frames_processed_total{engine="hmm"})";
  EXPECT_EQ(Sample(before, hmm_frames), 0);

  // One enrollment of 3 views, and one refused for its name.
  ASSERT_TRUE(Enroll(*models, "box", 3).ok());
  EXPECT_EQ(Enroll(*models, "box", 1).error_code(), grpc::StatusCode::ALREADY_EXISTS);

  // A session of 5 frames (the server's default engine, the HMM), scraped while it is open.
  {
    grpc::ClientContext context;
    auto stream = recognition->Session(&context);
    v1::SessionRequest open;
    open.mutable_open();
    ASSERT_TRUE(stream->Write(open));
    for (int k = 0; k < 5; ++k) {
      v1::SessionUpdate update;
      ASSERT_TRUE(stream->Write(Frame(Descriptor(k), k * 10.0)));
      ASSERT_TRUE(stream->Read(&update));
    }
    EXPECT_EQ(Sample(Scrape(metrics), "orbit_open_sessions"), 1);
    stream->WritesDone();
    ASSERT_TRUE(stream->Finish().ok());
  }
  // A session refused at its first frame: a descriptor value above 7.
  {
    grpc::ClientContext context;
    auto stream = recognition->Session(&context);
    v1::SessionRequest open;
    open.mutable_open();
    stream->Write(open);
    DescriptorValues bad = Descriptor(0);
    bad[17] = 9;
    stream->Write(Frame(bad, 0));
    stream->WritesDone();
    v1::SessionUpdate ignored;
    while (stream->Read(&ignored)) {
    }
    EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  // Two frames in one Recognize call with VCI.
  {
    grpc::ClientContext context;
    v1::RecognizeRequest request;
    request.mutable_options()->set_engine(v1::ENGINE_VCI);
    *request.add_frames() = Frame(Descriptor(1), 0).frame();
    *request.add_frames() = Frame(Descriptor(2), 10).frame();
    v1::RecognizeResponse response;
    ASSERT_TRUE(recognition->Recognize(&context, request, &response).ok());
  }

  EXPECT_EQ(ScrapeUntil(metrics, "orbit_open_sessions", 0), 0);
  const std::string after = Scrape(metrics);
  EXPECT_EQ(Sample(after, hmm_frames), 5);
  EXPECT_EQ(Sample(after, R"(orbit_frames_processed_total{engine="vci"})"), 2);
  EXPECT_EQ(Sample(after, R"(orbit_frame_processing_seconds_count{input="cedd"})"), 7);
  EXPECT_EQ(Sample(after, R"(orbit_frame_processing_seconds_bucket{input="cedd",le="+Inf"})"), 7);
  EXPECT_EQ(Sample(after, R"(orbit_frame_processing_seconds_count{input="image"})"), 0);
  EXPECT_GT(Sample(after, R"(orbit_frame_processing_seconds_sum{input="cedd"})"), 0);
  EXPECT_EQ(Sample(after, kInvalidField), 1);
  EXPECT_EQ(Sample(after, R"(orbit_refusals_total{code="ALREADY_EXISTS",reason="duplicate_name"})"),
            1);
  EXPECT_EQ(Sample(after, R"(orbit_enrollments_total{outcome="stored"})"), 1);
  EXPECT_EQ(Sample(after, R"(orbit_enrollments_total{outcome="refused"})"), 1);
  EXPECT_EQ(Sample(after, "orbit_enrollment_seconds_count"), 1);
  // Both enrollments reached the store; only the first committed.
  EXPECT_EQ(Sample(after, R"(orbit_store_write_seconds_count{operation="enroll"})"), 1);
  EXPECT_EQ(Sample(after, "orbit_index_objects"), 1);
  EXPECT_EQ(Sample(after, "orbit_index_views"), 3);
}

TEST(ServerMetricsTest, ServeRefusesToStartOnABadOrBusyMetricsAddress) {
  const testing::ScratchDir scratch;
  const std::string db = (scratch.path() / "models.db").string();
  const auto malformed = testing::StartServerExpectingRefusal(
      {"serve", "--db", db, "--listen", "127.0.0.1:0", "--metrics-listen", "localhost"});
  EXPECT_NE(malformed.exit_code, 0);
  EXPECT_THAT(malformed.log, HasSubstr("--metrics-listen: 'localhost' is not HOST:PORT"));
  EXPECT_THAT(malformed.log, ::testing::Not(HasSubstr("listening on")));

  const ServerMetrics metrics;
  const MetricsEndpoint taken("127.0.0.1:0", metrics);
  const auto busy = testing::StartServerExpectingRefusal(
      {"serve", "--db", db, "--listen", "127.0.0.1:0", "--metrics-listen", taken.address()});
  EXPECT_NE(busy.exit_code, 0);
  EXPECT_THAT(busy.log, HasSubstr("--metrics-listen: cannot listen on " + taken.address()));
  EXPECT_THAT(busy.log, ::testing::Not(HasSubstr("listening on")));

  const testing::CommandResult help = testing::RunOrbit("serve --help");
  EXPECT_THAT(help.out, HasSubstr("--metrics-listen"));
  EXPECT_THAT(help.out, HasSubstr("http://HOST:PORT/metrics"));
}

}  // namespace
}  // namespace orbit::server
