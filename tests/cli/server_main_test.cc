// orbit-server, the server machine's subset of `orbit` (cli/server_main.cc): it links none of
// the libraries only the device-side commands need, so the server image can leave them out, and
// its `serve` and `info` behave as `orbit`'s.
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/client_test_support.h"
#include "tests/support/health_check.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::Contains;
using ::testing::IsSupersetOf;
using ::testing::Not;
using testing::OrbitBinary;
using testing::RunCommand;
using testing::ServerProcess;

// Path of the built `orbit-server` binary, the server machine's subset of `orbit`.
std::string OrbitServerBinary() { return ORBIT_SERVER_BINARY; }

// The shared libraries `binary` loads, as the dynamic loader resolves them (ldd): each one's
// name up to ".so" ("libopencv_core" for libopencv_core.so.406).
std::set<std::string> LoadedLibraries(const std::string& binary) {
  const testing::CommandResult ldd = RunCommand("ldd " + binary);
  EXPECT_EQ(ldd.exit_code, 0) << ldd.err;
  std::set<std::string> names;
  const std::regex line(R"(^\s*(\S+?)\.so[.\d]* => )");
  std::istringstream in(ldd.out);
  for (std::string text; std::getline(in, text);) {
    std::smatch match;
    if (std::regex_search(text, match, line)) names.insert(match[1]);
  }
  return names;
}

// Libraries of the device-side commands: OpenCV's video analysis, video capture and contrib
// trackers (`orbit enroll --video`, `orbit recognize --video`, docs/capture.md), and the video
// decoders video capture brings.
const std::set<std::string>& DeviceOnlyLibraries() {
  static const std::set<std::string> libraries = {
      "libopencv_video", "libopencv_videoio", "libopencv_tracking", "libavcodec", "libavformat"};
  return libraries;
}

TEST(OrbitServerTest, LoadsNoLibraryOnlyTheDeviceCommandsNeed) {
  // The full tool loads them all: the check sees them where they are.
  EXPECT_THAT(LoadedLibraries(OrbitBinary()), IsSupersetOf(DeviceOnlyLibraries()));

  const std::set<std::string> server = LoadedLibraries(OrbitServerBinary());
  for (const std::string& library : DeviceOnlyLibraries()) {
    EXPECT_THAT(server, Not(Contains(library)));
  }
  // OpenCV's core, image processing and image decoding only (frames arrive as JPEG or PNG).
  for (const std::string& library : server) {
    if (library.starts_with("libopencv_")) {
      EXPECT_THAT(
          (std::set<std::string>{"libopencv_core", "libopencv_imgproc", "libopencv_imgcodecs"}),
          Contains(library));
    }
  }
  EXPECT_THAT(server, IsSupersetOf({"libopencv_imgcodecs", "libgrpc++", "libsqlite3", "libpq"}));
}

TEST(OrbitServerTest, ServesWhatOrbitInfoAndOrbitServerInfoReportAlike) {
  ServerProcess server({.binary = OrbitServerBinary()});
  EXPECT_EQ(testing::HealthStatus(server.address()), testing::kServing);

  const std::string enroll = OrbitBinary() + " enroll --server " + server.address() +
                             " --name obj7" + testing::CoilImageArguments(7, {0, 90, 180, 270});
  const testing::CommandResult enrolled = RunCommand(enroll);
  ASSERT_EQ(enrolled.exit_code, 0) << enrolled.err;

  const std::string info = " info --json --server " + server.address();
  const testing::CommandResult by_server = RunCommand(OrbitServerBinary() + info);
  const testing::CommandResult by_tool = RunCommand(OrbitBinary() + info);
  ASSERT_EQ(by_server.exit_code, 0) << by_server.err;
  ASSERT_EQ(by_tool.exit_code, 0) << by_tool.err;
  EXPECT_EQ(by_server.out, by_tool.out);
  const nlohmann::json answer = nlohmann::json::parse(by_server.out);
  EXPECT_EQ(answer["objects"], 1);
  EXPECT_EQ(answer["views"], 4);
}

// The subcommands `orbit-server --help` lists: the words at the start of its indented lines.
std::set<std::string> ListedCommands(const std::string& help) {
  std::set<std::string> commands;
  const std::regex line(R"(^  ([a-z]+) )");
  std::istringstream in(help);
  for (std::string text; std::getline(in, text);) {
    std::smatch match;
    if (std::regex_search(text, match, line)) commands.insert(match[1]);
  }
  return commands;
}

TEST(OrbitServerTest, HasOnlyTheServerMachinesCommands) {
  const testing::CommandResult version = RunCommand(OrbitServerBinary() + " --version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_THAT(version.out, ::testing::StartsWith("orbit-server "));

  const testing::CommandResult help = RunCommand(OrbitServerBinary() + " --help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  EXPECT_EQ(ListedCommands(help.out), (std::set<std::string>{"serve", "info", "token", "backup"}));
  // A device-side command is a usage error, as any unknown subcommand.
  const testing::CommandResult enroll = RunCommand(OrbitServerBinary() + " enroll --name obj7");
  EXPECT_EQ(enroll.exit_code, 2) << enroll.out;
}

}  // namespace
}  // namespace orbit
