// The metrics endpoint (server/metrics_endpoint.h): a real civetweb listener on loopback, spoken
// to with plain HTTP requests.
#include "server/metrics_endpoint.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "server/metrics.h"
#include "tests/support/http_client.h"

namespace orbit::server {
namespace {

using ::testing::HasSubstr;
using testing::HttpRequest;
using testing::HttpResponse;

TEST(MetricsEndpointTest, ServesTheRegistrysTextAtMetrics) {
  MetricsRegistry registry;
  Counter& scrapes = registry.AddCounter("test_things_total", "Things.").WithLabels({});
  MetricsEndpoint endpoint("127.0.0.1:0", registry);
  ASSERT_GT(endpoint.port(), 0);
  EXPECT_EQ(endpoint.address(), "127.0.0.1:" + std::to_string(endpoint.port()));

  const HttpResponse first = HttpRequest(endpoint.address(), "GET", "/metrics");
  EXPECT_EQ(first.status, 200);
  EXPECT_EQ(first.headers.at("content-type"), "text/plain; version=0.0.4; charset=utf-8");
  EXPECT_EQ(first.body,
            "# HELP test_things_total Things.\n# TYPE test_things_total counter\n"
            "test_things_total 0\n");
  EXPECT_EQ(first.headers.at("content-length"), std::to_string(first.body.size()));

  scrapes.Increment(3);
  const HttpResponse second = HttpRequest(endpoint.address(), "GET", "/metrics?ignored=1");
  EXPECT_EQ(second.status, 200);
  EXPECT_EQ(second.body, registry.Expose());
  EXPECT_THAT(second.body, HasSubstr("test_things_total 3\n"));

  const HttpResponse head = HttpRequest(endpoint.address(), "HEAD", "/metrics");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.body, "");
  EXPECT_EQ(head.headers.at("content-length"), std::to_string(second.body.size()));
}

TEST(MetricsEndpointTest, AnswersNothingButGetAndHeadOfMetrics) {
  MetricsRegistry registry;
  MetricsEndpoint endpoint("127.0.0.1:0", registry);
  const HttpResponse post = HttpRequest(endpoint.address(), "POST", "/metrics");
  EXPECT_EQ(post.status, 405);
  EXPECT_EQ(post.headers.at("allow"), "GET, HEAD");
  for (const char* path : {"/", "/metricsx", "/metrics/x", "/index.html", "/../etc/passwd"}) {
    EXPECT_EQ(HttpRequest(endpoint.address(), "GET", path).status, 404) << path;
  }
}

TEST(MetricsEndpointTest, APortInUseIsRefusedWithTheReason) {
  MetricsRegistry registry;
  MetricsEndpoint first("127.0.0.1:0", registry);
  try {
    MetricsEndpoint second(first.address(), registry);
    FAIL() << "a second endpoint bound " << first.address();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot bind to " + first.address()));
    EXPECT_THAT(e.what(), HasSubstr("Address already in use"));
  }
  // 192.0.2.1 (TEST-NET-1, RFC 5737) is no address of this machine.
  try {
    MetricsEndpoint elsewhere("192.0.2.1:0", registry);
    FAIL() << "bound 192.0.2.1";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("Cannot assign requested address"));
  }
}

TEST(MetricsEndpointTest, RefusesWhatIsNotHostColonPort) {
  MetricsRegistry registry;
  for (const char* address : {"", "nonsense", "127.0.0.1", ":9464", "127.0.0.1:", "127.0.0.1:65536",
                              "127.0.0.1:-1", "127.0.0.1:9464s", "127.0.0.1:1,127.0.0.1:2",
                              "[::1]:9464", "::1:9464", "127.0.0.1:94 64"}) {
    try {
      MetricsEndpoint endpoint(address, registry);
      ADD_FAILURE() << "accepted '" << address << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("is not HOST:PORT")) << address;
    }
  }
}

TEST(MetricsEndpointTest, StopsListeningWhenDestroyed) {
  MetricsRegistry registry;
  auto endpoint = std::make_unique<MetricsEndpoint>("127.0.0.1:0", registry);
  const std::string address = endpoint->address();
  EXPECT_EQ(HttpRequest(address, "GET", "/metrics").status, 200);
  endpoint.reset();
  EXPECT_THROW(HttpRequest(address, "GET", "/metrics"), std::runtime_error);
}

}  // namespace
}  // namespace orbit::server
