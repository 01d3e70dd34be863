// How `orbit` reports a failed call (cli/rpc_error_text.cc): the subcommand that failed, and for
// a server that is not there, the address it was looked for at and what to check.
#include <csignal>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilFile;
using testing::CoilImageArguments;
using testing::RunOrbit;
using testing::ServerProcess;

TEST(RpcErrorTextTest, AServerThatIsNotRunningIsNamedWithTheCommandThatNeededIt) {
  // The port of a server that has just stopped: nothing listens there.
  ServerProcess stopped;
  const std::string address = stopped.address();
  ASSERT_EQ(stopped.Stop(SIGTERM), 0);
  const std::string at = " --timeout 2 --server " + address;
  const std::string image = " --image " + CoilFile(1, 0);
  for (const std::string& command :
       {"info" + at, "recognize" + at + image,
        "enroll" + at + " --name mug" + image + " --azimuth 0", "list" + at}) {
    const std::string name = command.substr(0, command.find(' '));
    const testing::CommandResult down = RunOrbit(command);
    EXPECT_EQ(down.exit_code, 1) << command;
    const std::string expected_start = "orbit " + name + ": cannot reach a server at " + address;
    EXPECT_EQ(down.err.rfind(expected_start, 0), 0u) << down.err;
    EXPECT_NE(down.err.find("Connection refused): is `orbit serve` running at " + address + "?\n"),
              std::string::npos)
        << down.err;
    // gRPC's account of its attempt, and the call the library made first, are left out.
    EXPECT_EQ(down.err.find("ServerInfo"), std::string::npos) << down.err;
    EXPECT_EQ(down.err.find("failed to connect to all addresses"), std::string::npos) << down.err;
  }
}

TEST(RpcErrorTextTest, ARefusalFromARunningServerKeepsItsCallCodeAndMessage) {
  ServerProcess server;
  const std::string enroll =
      "enroll --server " + server.address() + " --name mug" + CoilImageArguments(1, {0, 20});
  ASSERT_EQ(RunOrbit(enroll).exit_code, 0);
  const testing::CommandResult again = RunOrbit(enroll);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_EQ(again.err.rfind("orbit enroll: Enroll: ALREADY_EXISTS: ", 0), 0u) << again.err;
  EXPECT_EQ(again.err.find("orbit serve"), std::string::npos) << again.err;
}

}  // namespace
}  // namespace orbit
