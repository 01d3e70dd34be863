// orbit demo (cli/demo_command.cc) against a real `orbit serve` process.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::OrbitBinary;
using testing::OutputLines;
using testing::RunCommand;
using testing::ServerProcess;

TEST(DemoCommandTest, DemoEnrollsItsObjectsOnceAndRecognisesTheOneItCircles) {
  ServerProcess server;
  const std::string demo = OrbitBinary() + " demo --json --server " + server.address();
  const auto first = RunCommand(demo);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("demo-box: enrolled (id 1, 36 views"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("demo-crate: enrolled (id 3, 36 views"), std::string::npos);
  std::vector<nlohmann::json> updates;
  for (const std::string& line : OutputLines(first.out)) {
    if (!line.empty() && line[0] == '{') updates.push_back(nlohmann::json::parse(line));
  }
  ASSERT_EQ(updates.size(), 8u) << first.out;
  EXPECT_EQ(updates.back()["frame"], 7);
  EXPECT_EQ(updates.back()["candidates"][0]["name"], "demo-can");

  const auto second = RunCommand(demo + " --object demo-crate --frames 3");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("demo-can: already enrolled (id 2, 36 views)"), std::string::npos)
      << second.out;
  const std::vector<std::string> lines = OutputLines(second.out);
  std::string last_update;
  for (const std::string& line : lines) {
    if (!line.empty() && line[0] == '{') last_update = line;
  }
  ASSERT_FALSE(last_update.empty()) << second.out;
  EXPECT_EQ(nlohmann::json::parse(last_update)["candidates"][0]["name"], "demo-crate");
}

}  // namespace
}  // namespace orbit
