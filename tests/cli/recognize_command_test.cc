// orbit enroll and orbit recognize (cli/enroll_command.cc, cli/recognize_command.cc,
// cli/update_format.cc) against a real `orbit serve` process, as a user would type them.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include "client/image_file.h"
#include "core/base/angles.h"
#include "evaluation/dataset.h"

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
  EXPECT_EQ(info_json["variant"], "cedd-soft-hsv-hog");
  EXPECT_EQ(info_json["session_defaults"]["rejection"], "calibrated");
  EXPECT_EQ(info_json["session_defaults"]["false_accept_rate"], 0.15);
  EXPECT_EQ(info_json["session_defaults"]["known_accept_rate"], 0.95);
  EXPECT_EQ(info_json["limits"]["max_image_pixels"], 16777216);
  EXPECT_EQ(info_json["limits"]["max_hmm_cells"], 1024);
  EXPECT_EQ(info_json["limits"]["max_enrollment_bytes"], 256 << 20);
  EXPECT_EQ(info_json["limits"]["max_recognize_calls_per_token"], 8);

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
  EXPECT_LE(std::abs(AzimuthChange(last["pose"]["azimuth_deg"].get<double>(), 90)), 15)
      << lines.back();

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
  // Both ways the command takes azimuths are named.
  EXPECT_NE(uneven.err.find("orbit: 4 images and 1 azimuth: give one --azimuth per --image, or no "
                            "--azimuth at all (frames without azimuth, as from a device without "
                            "a compass)\n"),
            std::string::npos)
      << uneven.err;
}

// `orbit walk` renders a capture and prints "... first box X,Y,W,H"; returns "X,Y,W,H".
std::string RenderWalk(const std::string& dir, const std::string& name, int object,
                       const std::string& shape) {
  const auto r = RunCommand(OrbitBinary() + " walk --coil " + testing::CoilDir() + " --object " +
                            std::to_string(object) + " --video " + dir + "/" + name +
                            ".avi --orientation " + dir + "/" + name + ".csv " + shape);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto at = r.out.find("first box ");
  if (at == std::string::npos) return "";
  return r.out.substr(at + 10, r.out.find('\n', at) - at - 10);
}

TEST(RecognizeCommandTest, EnrollsFromWalksAndRecognisesEachFromASecondWalk) {
  ServerProcess server;
  const testing::ScratchDir scratch;
  const std::string dir = scratch.path().string();
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  const std::vector<int> objects = {3, 8};
  // CSRT's boxes, on which the acceptance counts below were set: on object 3's second walk it
  // shrinks its box inside the object, leaving out the clutter a tight box holds. With tight
  // boxes (the default tracker's, or the true boxes) fewer of these updates are accepted, none
  // wrongly (docs/results/capture.md, "Hit rate from walks").
  const std::string tracker = " --tracker csrt";
  for (int object : objects) {
    // A whole walk round the object: 72 frames, 10 fps, a view every 5 degrees.
    const std::string name = "enroll" + std::to_string(object);
    const std::string box = RenderWalk(dir, name, object, "--frames 72 --seed 1");
    const auto r = RunCommand(orbit + "enroll" + at + " --name obj" + std::to_string(object) +
                              " --video " + dir + "/" + name + ".avi --orientation " + dir + "/" +
                              name + ".csv --box " + box + tracker);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = OutputLines(r.out);
    ASSERT_GE(lines.size(), 3u);
    // "enrolled obj3 (id 1, 48 views)": blurred, noisy, lost frames and steps the noisy
    // compass skipped leave some of the 72 steps empty, but no gap wider than 30 degrees.
    int views = 0;
    ASSERT_EQ(std::sscanf(lines[0].c_str(),
                          ("enrolled obj" + std::to_string(object) + " (id %*d, %d views)").c_str(),
                          &views),
              1)
        << lines[0];
    EXPECT_GE(views, 40);
    EXPECT_EQ(lines[1].rfind("  capture: 72 frames, ", 0), 0u) << lines[1];
    EXPECT_NE(lines[1].find("views in " + std::to_string(views) + " of 72 steps of 5 degrees"),
              std::string::npos)
        << lines[1];
    // One line per step, then the views' gaps wider than a step, then the server's report.
    ASSERT_GE(lines.size(), 2u + 72 + 1);
    EXPECT_EQ(lines[2].rfind("  step 0-5: ", 0), 0u) << lines[2];
    EXPECT_EQ(lines[73].rfind("  step 355-360: ", 0), 0u) << lines[73];
    EXPECT_NE(std::find(lines.begin(), lines.end(), "  coverage: no gap wider than 30 degrees"),
              lines.end())
        << r.out;
  }
  for (int object : objects) {
    // A second, shorter walk on another background, from azimuth 100.
    const std::string name = "query" + std::to_string(object);
    const std::string box =
        RenderWalk(dir, name, object, "--frames 24 --turn 120 --start 100 --seed 7");
    const auto r =
        RunCommand(orbit + "recognize --json --fast --top-k 2" + at + " --video " + dir + "/" +
                   name + ".avi --orientation " + dir + "/" + name + ".csv --box " + box + tracker);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = OutputLines(r.out);
    EXPECT_EQ(lines.size(), 24u);  // one update per frame, none lost
    // What the user is told: the first candidate of an accepted update; an UNKNOWN update names
    // no object.
    int right = 0, wrong = 0;
    for (const std::string& line : lines) {
      const auto update = nlohmann::json::parse(line);
      if (update["decision"] != "ACCEPT") continue;
      (update["candidates"][0]["name"] == "obj" + std::to_string(object) ? right : wrong) += 1;
    }
    // Never a confident wrong answer, and each object recognised on the other background: the
    // appearance channels describe the object, its background's colours taken off
    // (docs/design.md#foreground-estimate); counting them, object 8's second walk was UNKNOWN
    // on every frame.
    EXPECT_EQ(wrong, 0) << "object " << object;
    EXPECT_GE(right, 16) << "object " << object;
  }

  // A log that stops before the video ends is refused before anything is sent.
  const std::string log = scratch.Write("short.csv", "timestamp_ms,azimuth_deg\n0,0\n1000,90\n");
  const auto short_log =
      RunCommand(orbit + "recognize" + at + " --video " + dir + "/query3.avi --orientation " + log);
  EXPECT_EQ(short_log.exit_code, 1);
  EXPECT_NE(short_log.err.find(log + " does not cover frame 23 (at 2300 ms): it covers "
                                     "timestamp_ms 0 to 1000"),
            std::string::npos)
      << short_log.err;
  // A still image is no video, though a video reader would take it for one frame.
  const auto still =
      RunCommand(orbit + "recognize" + at + " --video " + CoilFile(3, 0) + " --orientation " + log);
  EXPECT_EQ(still.exit_code, 1);
  EXPECT_NE(still.err.find("orbit: video " + CoilFile(3, 0) + " is a still image: "),
            std::string::npos)
      << still.err;
  const auto no_log = RunCommand(orbit + "recognize" + at + " --video " + dir + "/query3.avi");
  EXPECT_EQ(no_log.exit_code, 2) << no_log.err;
  const auto both =
      RunCommand(orbit + "enroll" + at + " --name x --video " + dir + "/query3.avi --orientation " +
                 dir + "/query3.csv" + CoilImageArguments(1, {0}));
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.err.find("give --video or --image, not both"), std::string::npos) << both.err;
}

// Two objects side by side in every frame: the box says which one the user means, and the
// answer follows it. eth-80-dev's apple1 and car1 (and cup1, a third object) are enrolled from
// their boxed views every 45 degrees; the frames hold the views between them, apple1 on the
// left half, car1 on the right.
TEST(RecognizeCommandTest, TheBoxSaysWhichObjectOfTheFrameIsRecognised) {
  ServerProcess server;
  const testing::ScratchDir scratch;
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  const std::filesystem::path eth = testing::DataDir() / "eth-80-dev";
  const auto view = [&](const std::string& object, int azimuth) {
    char name[64];
    std::snprintf(name, sizeof name, "images/%s-090-%03d.jpg", object.c_str(), azimuth);
    return (eth / name).string();
  };
  for (const std::string object : {"apple1", "car1", "cup1"}) {
    std::string views;
    for (int azimuth = 0; azimuth < 360; azimuth += 45) {
      views += " --image " + view(object, azimuth) + " --azimuth " + std::to_string(azimuth);
    }
    const auto r = RunCommand(orbit + "enroll" + at + " --name " + object + views + " --boxes " +
                              (eth / "boxes.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::map<std::string, ImageBox> boxes = ReadBoxes(eth / "boxes.csv");
  const auto box_of = [&](const std::string& object, int azimuth, int shift) {
    const ImageBox& box =
        boxes.at(std::filesystem::path(view(object, azimuth)).lexically_normal().string());
    return " --box " + std::to_string(box.x + shift) + "," + std::to_string(box.y) + "," +
           std::to_string(box.width) + "," + std::to_string(box.height);
  };
  std::string frames, apple_boxes, car_boxes;
  for (const int azimuth : {22, 68, 112, 158}) {
    cv::Mat frame;
    cv::hconcat(ReadImageFile(view("apple1", azimuth)), ReadImageFile(view("car1", azimuth)),
                frame);
    const std::string file = (scratch / ("frame" + std::to_string(azimuth) + ".png")).string();
    ASSERT_TRUE(cv::imwrite(file, frame));
    frames += " --image " + file + " --azimuth " + std::to_string(azimuth);
    apple_boxes += box_of("apple1", azimuth, 0);
    car_boxes += box_of("car1", azimuth, 256);  // the right half
  }
  for (const auto& [object, boxes_given] :
       {std::pair{"apple1", apple_boxes}, std::pair{"car1", car_boxes}}) {
    const auto r = RunCommand(orbit + "recognize --json" + at + frames + boxes_given);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = OutputLines(r.out);
    ASSERT_EQ(lines.size(), 4u) << r.out;
    for (const std::string& line : lines) {
      EXPECT_EQ(nlohmann::json::parse(line)["candidates"][0]["name"], object) << line;
    }
  }
}

}  // namespace
}  // namespace orbit
