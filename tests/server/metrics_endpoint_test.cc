// The metrics endpoint (server/metrics_endpoint.h): a real listener on loopback, spoken to with
// plain HTTP requests.
#include "server/metrics_endpoint.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "server/server_metrics.h"
#include "tests/support/http_client.h"

namespace orbit::server {
namespace {

using ::testing::HasSubstr;
using testing::HttpRequest;
using testing::HttpResponse;

TEST(MetricsEndpointTest, ServesTheServersMetricsAtMetrics) {
  ServerMetrics metrics;
  MetricsEndpoint endpoint("127.0.0.1:0", metrics);
  ASSERT_GT(endpoint.port(), 0);
  EXPECT_EQ(endpoint.address(), "127.0.0.1:" + std::to_string(endpoint.port()));

  const HttpResponse first = HttpRequest(endpoint.address(), "GET", "/metrics");
  EXPECT_EQ(first.status, 200);
  EXPECT_THAT(first.headers.at("content-type"), HasSubstr("text/plain"));
  EXPECT_THAT(first.body, HasSubstr("orbit_frames_processed_total{engine=\"hmm\"} 0\n"));

  metrics.ForEngine(v1::ENGINE_HMM).Record(FrameInput::kCedd, std::chrono::microseconds(40));
  const HttpResponse second = HttpRequest(endpoint.address(), "GET", "/metrics");
  EXPECT_EQ(second.status, 200);
  EXPECT_THAT(second.body, HasSubstr("orbit_frames_processed_total{engine=\"hmm\"} 1\n"));
  EXPECT_THAT(second.body, HasSubstr("orbit_frame_processing_seconds_count{input=\"cedd\"} 1\n"));

  EXPECT_EQ(HttpRequest(endpoint.address(), "GET", "/index.html").status, 404);
}

TEST(MetricsEndpointTest, APortInUseOrAForeignAddressIsRefusedNamingIt) {
  ServerMetrics metrics;
  MetricsEndpoint first("127.0.0.1:0", metrics);
  try {
    MetricsEndpoint second(first.address(), metrics);
    FAIL() << "a second endpoint bound " << first.address();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot listen on " + first.address()));
  }
  // 192.0.2.1 (TEST-NET-1, RFC 5737) is no address of this machine.
  EXPECT_THROW(MetricsEndpoint("192.0.2.1:0", metrics), std::runtime_error);
}

TEST(MetricsEndpointTest, RefusesWhatIsNotHostColonPort) {
  ServerMetrics metrics;
  for (const char* address : {"", "nonsense", "127.0.0.1", ":9464", "127.0.0.1:", "127.0.0.1:65536",
                              "127.0.0.1:-1", "127.0.0.1:9464s", "127.0.0.1:1,127.0.0.1:2",
                              "[::1]:9464", "::1:9464", "127.0.0.1:94 64"}) {
    try {
      MetricsEndpoint endpoint(address, metrics);
      ADD_FAILURE() << "accepted '" << address << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("is not HOST:PORT")) << address;
    }
  }
}

TEST(MetricsEndpointTest, StopsListeningWhenDestroyed) {
  ServerMetrics metrics;
  auto endpoint = std::make_unique<MetricsEndpoint>("127.0.0.1:0", metrics);
  const std::string address = endpoint->address();
  EXPECT_EQ(HttpRequest(address, "GET", "/metrics").status, 200);
  endpoint.reset();
  EXPECT_THROW(HttpRequest(address, "GET", "/metrics"), std::runtime_error);
}

}  // namespace
}  // namespace orbit::server
