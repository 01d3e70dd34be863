// Connection admission against a real `orbit serve` under a small descriptor limit, flooded with
// raw connections (docs/design.md#connection-admission).
#include "server/connection_admission.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/models.grpc.pb.h"
#include "tests/support/http_client.h"
#include "tests/support/metric_sample.h"
#include "tests/support/raw_connections.h"
#include "tests/support/server_process.h"
#include "tests/support/well_behaved_session.h"

namespace orbit {
namespace {

using testing::RawConnections;
using testing::RawGreeting;
using testing::ServerProcess;
using testing::ServerProcessOptions;

// ServerInfo on a channel of its own, as a new client asks it, within `deadline`.
grpc::Status AskInfo(const std::string& address,
                     std::chrono::seconds deadline = std::chrono::seconds(5)) {
  auto stub = v1::Models::NewStub(grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + deadline);
  v1::ServerInfoResponse response;
  return stub->ServerInfo(&context, v1::ServerInfoRequest(), &response);
}

// More idle connections than `ulimit -n 200` has descriptors (the review's flood): the server
// refuses what it has no room for, a client already connected keeps being answered (a device's
// session keeps its p99), and once the flood ends a new client is answered at once. Without
// admission gRPC's listener closed for good at the first EMFILE and every later call timed out.
TEST(ConnectionAdmission, ServesAgainAfterAFloodLargerThanItsDescriptorTable) {
  ServerProcessOptions options;
  options.descriptor_limit = 200;
  options.metrics = true;
  ServerProcess server(options);
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto connected = v1::Models::NewStub(channel);
  testing::WellBehavedSession device(channel);
  const auto baseline = device.P99(50);
  const auto ask_connected = [&] {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
    v1::ServerInfoResponse response;
    return connected->ServerInfo(&context, v1::ServerInfoRequest(), &response);
  };
  ASSERT_TRUE(ask_connected().ok());
  {
    RawConnections flood(server.port(), 260, RawGreeting::kPrefaceSettings);
    EXPECT_EQ(flood.connected(), 260) << "the kernel completes the handshakes for the listener";
    EXPECT_TRUE(ask_connected().ok()) << "a connected client is answered during the flood";
    const auto during = device.P99(50);
    EXPECT_LE(during, testing::KeptP99(baseline))
        << "p99 " << testing::Milliseconds(during) << " ms during the flood, "
        << testing::Milliseconds(baseline) << " ms before";
    // Refused connections are closed by the server at once: the descriptors the server keeps
    // free are never lent to the flood.
    EXPECT_GE(flood.ClosedByServerWithin(std::chrono::seconds(2)), 260 - 200);
  }
  EXPECT_TRUE(device.Close().ok());
  const grpc::Status after = AskInfo(server.address());
  EXPECT_TRUE(after.ok()) << "after the flood: " << after.error_message() << "\n" << server.Log();
  // The operator is told, in the log and in the metrics.
  EXPECT_NE(server.Log().find("refusing new connections"), std::string::npos) << server.Log();
  const std::string metrics =
      testing::HttpRequest(server.metrics_address(), "GET", "/metrics").body;
  EXPECT_GE(testing::Sample(metrics, "orbit_connections_refused_total"), 260 - 200);
}

// A flood that never closes its connections: the idle limit gives the descriptors back, and new
// clients are answered while the flood still holds its side open.
TEST(ConnectionAdmission, ServesNewClientsWhileAFloodStillHoldsItsConnections) {
  ServerProcessOptions options;
  options.descriptor_limit = 200;
  options.extra_args = {"--connection-idle-timeout", "2", "--handshake-timeout", "2"};
  ServerProcess server(options);
  RawConnections idle(server.port(), 200, RawGreeting::kPrefaceSettings);
  RawConnections silent(server.port(), 60, RawGreeting::kNothing);
  ASSERT_EQ(idle.connected() + silent.connected(), 260);
  EXPECT_EQ(idle.ClosedByServerWithin(std::chrono::seconds(10)), idle.connected());
  EXPECT_EQ(silent.ClosedByServerWithin(std::chrono::seconds(10)), silent.connected());
  const grpc::Status status = AskInfo(server.address());
  EXPECT_TRUE(status.ok()) << status.error_message() << "\n" << server.Log();
}

}  // namespace
}  // namespace orbit
