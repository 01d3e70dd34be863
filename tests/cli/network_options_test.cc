// The options every networked subcommand shares (cli/network_options.cc): --server, --token,
// --token-file, --tls-ca, --timeout; unreachable servers and bad arguments reported clearly.
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilFile;
using testing::CoilImageArguments;
using testing::EveryTwentyDegrees;
using testing::OrbitBinary;
using testing::OutputLines;
using testing::RunCommand;
using testing::ServerProcess;

TEST(NetworkOptionsTest, ReportsUnreachableServersAndBadArguments) {
  const std::string orbit = OrbitBinary() + " ";
  ServerProcess server;
  const std::string address = server.address();
  ASSERT_EQ(server.Stop(SIGTERM), 0);
  const auto down = RunCommand(orbit + "info --timeout 2 --server " + address);
  EXPECT_EQ(down.exit_code, 1);
  EXPECT_NE(down.err.find("is `orbit serve` running at " + address + "?"), std::string::npos)
      << down.err;

  const auto unpaired = RunCommand(orbit + "recognize --server " + address + " --image " +
                                   CoilFile(1, 0) + " --azimuth 0 --azimuth 5");
  EXPECT_EQ(unpaired.exit_code, 1);
  EXPECT_NE(unpaired.err.find("1 image and 2 azimuths: give one --azimuth per --image, or no "
                              "--azimuth at all"),
            std::string::npos)
      << unpaired.err;
}

TEST(NetworkOptionsTest, RefusesAServerThatIsNotHostAndPort) {
  // No server is needed: each value is refused as a usage error (exit 2) before any dialling,
  // naming the flag and the form to give instead.
  struct Case {
    std::string server;
    std::string says;
  };
  const std::vector<Case> cases = {
      {"127.0.0.1", "--server: 127.0.0.1 has no port: give HOST:PORT, e.g. 127.0.0.1:50051"},
      {"edge.local:", "--server: edge.local: has no port: give HOST:PORT, e.g. edge.local:50051"},
      {":50051", "--server: :50051 has no host: give HOST:PORT"},
      {"''", "--server: no address: give HOST:PORT"},
      {"127.0.0.1:0", "--server: port 0 is out of range: give HOST:PORT with a PORT of 1 to 65535"},
      {"127.0.0.1:65536", "--server: port 65536 is out of range"},
      {"127.0.0.1:http", "--server: port \"http\" is not a number: give HOST:PORT"},
      {"::1:50051", "--server: ::1:50051 is ambiguous: write an IPv6 host in brackets"},
      {"[::1]", "--server: [::1] has no port: give HOST:PORT, e.g. [::1]:50051"},
  };
  for (const Case& c : cases) {
    for (const char* command : {"info", "recognize --image x.png", "list"}) {
      const auto refused =
          RunCommand(OrbitBinary() + " " + command + " --timeout 2 --server " + c.server);
      EXPECT_EQ(refused.exit_code, 2) << command << " --server " << c.server << "\n" << refused.err;
      EXPECT_NE(refused.err.find(c.says), std::string::npos)
          << command << " --server " << c.server << "\n"
          << refused.err;
    }
  }
}

TEST(NetworkOptionsTest, TokensAndTlsFromTheCommandLine) {
  const testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  ServerProcess server(testing::SecuredServerOptions(dir, "edge.test", "admin-token-0123456",
                                                     "reader-token-0123456"));
  const std::string net = " --server " + server.address() + " --tls-ca " +
                          (dir / "cert.pem").string() + " --tls-server-name edge.test";
  const std::string orbit = OrbitBinary() + " ";
  const std::string reader_file = " --token-file " + (dir / "reader.token").string();

  const auto enrolled = RunCommand(orbit + "enroll" + net + " --token admin-token-0123456" +
                                   " --name obj1" + CoilImageArguments(1, EveryTwentyDegrees()));
  ASSERT_EQ(enrolled.exit_code, 0) << enrolled.err;
  const auto denied = RunCommand(orbit + "enroll" + net + reader_file + " --name obj2" +
                                 CoilImageArguments(2, {0, 20}));
  EXPECT_EQ(denied.exit_code, 1);
  EXPECT_NE(denied.err.find("PERMISSION_DENIED"), std::string::npos) << denied.err;
  const auto anonymous = RunCommand("env -u ORBIT_TOKEN " + orbit + "info" + net);
  EXPECT_EQ(anonymous.exit_code, 1);
  EXPECT_NE(anonymous.err.find("UNAUTHENTICATED"), std::string::npos) << anonymous.err;

  // The token from the environment; a token file on the command line wins over it.
  EXPECT_EQ(RunCommand("ORBIT_TOKEN=reader-token-0123456 " + orbit + "info" + net).exit_code, 0);
  const auto file_wins =
      RunCommand("ORBIT_TOKEN=stale-token-000000000 " + orbit + "list" + net + reader_file);
  ASSERT_EQ(file_wins.exit_code, 0) << file_wins.err;
  EXPECT_EQ(file_wins.out.rfind("1 obj1 cedd-soft-hsv-hog 18 ", 0), 0u) << file_wins.out;
  const auto recognised =
      RunCommand(orbit + "recognize --json" + net + reader_file + CoilImageArguments(1, {30, 50}));
  ASSERT_EQ(recognised.exit_code, 0) << recognised.err;
  EXPECT_EQ(nlohmann::json::parse(OutputLines(recognised.out).back())["candidates"][0]["name"],
            "obj1");

  // Plaintext against the TLS port fails.
  EXPECT_NE(
      RunCommand(orbit + "info --timeout 3 --server " + server.address() + reader_file).exit_code,
      0);
}

}  // namespace
}  // namespace orbit
