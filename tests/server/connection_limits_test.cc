// Connection limits on a real `orbit serve`: what a connection that holds no call is left with.
#include "server/connection_limits.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "tests/support/raw_connections.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using server::ConnectionLimits;
using server::ValidateConnectionLimits;
using testing::RawConnections;
using testing::RawGreeting;
using testing::ServerProcess;
using testing::ServerProcessOptions;

std::string ValidationError(const ConnectionLimits& limits) {
  try {
    ValidateConnectionLimits(limits);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ConnectionLimits, DefaultsAreValidAndAValueOutOfRangeIsNamedWithItsRange) {
  EXPECT_EQ(ValidationError(ConnectionLimits()), "");
  ConnectionLimits no_idle;
  no_idle.idle_timeout_seconds = 0;
  EXPECT_EQ(ValidationError(no_idle), "--connection-idle-timeout is 0, expected 1..86400");
  ConnectionLimits small_reserve;
  small_reserve.descriptor_reserve = 2;
  EXPECT_EQ(ValidationError(small_reserve), "--descriptor-reserve is 2, expected 8..65536");
}

// An HTTP/2 connection with no call is closed after --connection-idle-timeout, and one that
// never sends its preface after --handshake-timeout; gRPC's defaults keep both forever and two
// minutes.
TEST(ConnectionLimits, ClosesConnectionsThatHoldNoCall) {
  ServerProcessOptions options;
  options.extra_args = {"--connection-idle-timeout", "1", "--handshake-timeout", "1"};
  ServerProcess server(options);
  RawConnections idle(server.port(), 5, RawGreeting::kPrefaceSettings);
  RawConnections silent(server.port(), 5, RawGreeting::kNothing);
  ASSERT_EQ(idle.connected(), 5);
  ASSERT_EQ(silent.connected(), 5);
  EXPECT_EQ(idle.ClosedByServerWithin(std::chrono::seconds(6)), 5);
  EXPECT_EQ(silent.ClosedByServerWithin(std::chrono::seconds(6)), 5);
}

TEST(ConnectionLimits, KeepsAnIdleConnectionOpenUntilItsTimeout) {
  ServerProcessOptions options;
  options.extra_args = {"--connection-idle-timeout", "30"};
  ServerProcess server(options);
  RawConnections idle(server.port(), 3, RawGreeting::kPrefaceSettings);
  EXPECT_EQ(idle.ClosedByServerWithin(std::chrono::seconds(3)), 0);
}

TEST(ConnectionLimits, ServeRefusesAnOutOfRangeLimitNamingItsFlag) {
  const auto refused = testing::StartServerExpectingRefusal(
      {"serve", "--db", "/nonexistent/never-created.db", "--keepalive", "0"});
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.log.find("--keepalive is 0, expected 1..86400"), std::string::npos)
      << refused.log;
}

}  // namespace
}  // namespace orbit
