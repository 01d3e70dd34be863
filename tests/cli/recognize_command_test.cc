// orbit enroll and orbit recognize (cli/enroll_command.cc, cli/recognize_command.cc,
// cli/update_format.cc) against a real `orbit serve` process, as a user would type them.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/angles.h"
#include <nlohmann/json.hpp>

#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilImageArguments;
using testing::EveryTwentyDegrees;
using testing::OrbitBinary;
using testing::OutputLines;
using testing::RunCommand;
using testing::ServerProcess;

TEST(RecognizeCommandTest, EnrollsThenRecognisesWithJsonAndTextOutput) {
  ServerProcess server;
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  for (int object = 1; object <= 3; ++object) {
    const auto r = RunCommand(orbit + "enroll" + at + " --name obj" + std::to_string(object) +
                              CoilImageArguments(object, EveryTwentyDegrees()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Every 20 degrees: no gap; the report says so under the object's line.
    EXPECT_EQ(OutputLines(r.out)[0], "enrolled obj" + std::to_string(object) + " (id " +
                                         std::to_string(object) + ", 18 views)");
    EXPECT_EQ(OutputLines(r.out)[1], "  coverage: no gap wider than 30 degrees");
  }
  const auto again =
      RunCommand(orbit + "enroll" + at + " --name obj1" + CoilImageArguments(1, {0, 20}));
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("ALREADY_EXISTS"), std::string::npos) << again.err;

  const auto info = RunCommand(orbit + "info --json" + at);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto info_json = nlohmann::json::parse(info.out);
  EXPECT_EQ(info_json["objects"], 3);
  EXPECT_EQ(info_json["views"], 54);
  EXPECT_EQ(info_json["variant"], "cedd-robust");
  EXPECT_EQ(info_json["session_defaults"]["rejection"], "calibrated");
  EXPECT_EQ(info_json["session_defaults"]["false_accept_rate"], 0.15);
  EXPECT_EQ(info_json["limits"]["max_image_pixels"], 16777216);
  EXPECT_EQ(info_json["limits"]["max_hmm_cells"], 1024);

  // Object 2 between its enrolled views, the compass 90 degrees off.
  const std::string frames = CoilImageArguments(2, {30, 50, 70, 90}, 90);
  const auto json = RunCommand(orbit + "recognize --json --top-k 2" + at + frames);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const std::vector<std::string> lines = OutputLines(json.out);
  ASSERT_EQ(lines.size(), 4u) << json.out;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const auto update = nlohmann::json::parse(lines[k]);
    EXPECT_EQ(update["frame"], k);
    EXPECT_TRUE(update["decision"] == "ACCEPT" || update["decision"] == "UNKNOWN" ||
                update["decision"] == "UNDECIDED")
        << lines[k];
    EXPECT_TRUE(update["move"] == "LEFT" || update["move"] == "RIGHT" || update["move"] == "NONE")
        << lines[k];
    const auto& candidates = update["candidates"];
    ASSERT_TRUE(candidates.is_array());
    ASSERT_GE(candidates.size(), 1u);
    ASSERT_LE(candidates.size(), 2u);
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      EXPECT_GE(candidates[i - 1]["score"].get<double>(), candidates[i]["score"].get<double>());
    }
    EXPECT_TRUE(candidates[0].contains("id"));
  }
  const auto last = nlohmann::json::parse(lines.back());
  EXPECT_EQ(last["candidates"][0]["name"], "obj2");
  EXPECT_EQ(last["candidates"][0]["id"], 2);
  EXPECT_EQ(last["decision"], "ACCEPT");
  EXPECT_GT(last["confidence"].get<double>(), 0.5);
  // Its latest frame shows obj2 at 90 degrees, between the enrolled 80 and 100.
  EXPECT_LE(std::abs(AzimuthChange(last["pose"]["azimuth_deg"].get<double>(), 90)), 15) << lines.back();

  const auto text = RunCommand(orbit + "recognize" + at + frames);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::vector<std::string> text_lines = OutputLines(text.out);
  ASSERT_EQ(text_lines.size(), 4u);
  EXPECT_EQ(text_lines[3].rfind("frame 3  ACCEPT     confidence ", 0), 0u) << text_lines[3];
  EXPECT_NE(text_lines[3].find(" seen from "), std::string::npos) << text_lines[3];
  EXPECT_NE(text_lines[3].find(" obj2 (id 2) "), std::string::npos) << text_lines[3];

  // No --azimuth at all: a device without an orientation sensor, recognised from the images.
  std::string images;
  for (const int azimuth : {30, 50, 70, 90}) {
    images += " --image " + testing::CoilDir() + "/obj2__" + std::to_string(azimuth) + ".png";
  }
  const auto blind = RunCommand(orbit + "recognize --json" + at + images);
  ASSERT_EQ(blind.exit_code, 0) << blind.err;
  ASSERT_EQ(OutputLines(blind.out).size(), 4u);
  EXPECT_EQ(nlohmann::json::parse(OutputLines(blind.out).back())["candidates"][0]["name"], "obj2");
  const auto uneven = RunCommand(orbit + "recognize" + at + images + " --azimuth 30");
  EXPECT_EQ(uneven.exit_code, 1);
  EXPECT_NE(uneven.err.find("give one --azimuth per --image (4 images, 1 azimuths)"),
            std::string::npos)
      << uneven.err;
}

}  // namespace
}  // namespace orbit
