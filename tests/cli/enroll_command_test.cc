// orbit enroll (cli/enroll_command.cc) from still images with the object's box (--box, --boxes,
// --box-margin; cli/box_arguments.h), against a real `orbit serve` process on real eth-80-dev
// images, as a user would type it. Enrolling from images and from videos without boxes is
// tested with recognition (tests/cli/recognize_command_test.cc).
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "client/connection.h"
#include "client/image_file.h"
#include "client/models_client.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::ServerProcess;

// Two views of eth-80-dev's apple1 and their boxes in boxes.csv.
struct AppleViews {
  std::string eth = (testing::DataDir() / "eth-80-dev").string();
  std::string boxes = eth + "/boxes.csv";
  std::string front = eth + "/images/apple1-090-000.jpg";  // 256x256, box 32,32,192,191
  std::string side = eth + "/images/apple1-090-045.jpg";   // 256x256, box 30,31,196,193
};

TEST(EnrollCommandTest, ABoxStoresTheViewsOfItsRegionCutOutBeforehand) {
  ServerProcess server;
  const ScratchDir dir;
  const AppleViews apple;
  // The regions cut by hand: each box grown by a tenth of its width and height a side (the
  // default margin), round(19.2) = 19 and round(19.1) = 19 for the front, round(19.6) = 20 and
  // round(19.3) = 19 for the side.
  const std::string front_cut = (dir / "front.png").string();
  const std::string side_cut = (dir / "side.png").string();
  ASSERT_TRUE(cv::imwrite(front_cut, ReadImageFile(apple.front)(cv::Rect(13, 13, 230, 229))));
  ASSERT_TRUE(cv::imwrite(side_cut, ReadImageFile(apple.side)(cv::Rect(10, 12, 236, 231))));

  const std::string at = "enroll --server " + server.address();
  const auto enroll = [&](const std::string& arguments) {
    const auto r = RunOrbit(at + arguments);
    EXPECT_EQ(r.exit_code, 0) << arguments << "\n" << r.err;
  };
  enroll(" --name cut --image " + front_cut + " --azimuth 0 --image " + side_cut + " --azimuth 45");
  enroll(" --name boxed --image " + apple.front + " --azimuth 0 --box 32,32,192,191 --image " +
         apple.side + " --azimuth 45 --box 30,31,196,193");
  enroll(" --name listed --image " + apple.front + " --azimuth 0 --image " + apple.side +
         " --azimuth 45 --boxes " + apple.boxes);
  enroll(" --name whole --image " + apple.front + " --azimuth 0 --image " + apple.side +
         " --azimuth 45");
  enroll(" --name tight --image " + apple.front + " --azimuth 0 --box 32,32,192,191 --image " +
         apple.side + " --azimuth 45 --box 30,31,196,193 --box-margin 0");

  const Connection connection(testing::At(server.address()));
  const auto views = [&](const std::string& name) {
    return ModelsClient(connection).GetObject(ObjectByName(name), true);
  };
  const v1::GetObjectResponse cut = views("cut");
  ASSERT_EQ(cut.views_size(), 2);
  for (const std::string name : {"boxed", "listed"}) {
    const v1::GetObjectResponse boxed = views(name);
    ASSERT_EQ(boxed.views_size(), 2) << name;
    for (int f = 0; f < 2; ++f) {
      EXPECT_EQ(boxed.views(f).cedd(), cut.views(f).cedd()) << name << " view " << f;
      EXPECT_EQ(boxed.views(f).typical_distance(), cut.views(f).typical_distance())
          << name << " view " << f;
    }
  }
  // The box matters: the whole image, and the box without its margin, describe other pixels.
  for (const std::string name : {"whole", "tight"}) {
    const v1::GetObjectResponse other = views(name);
    ASSERT_EQ(other.views_size(), 2) << name;
    EXPECT_NE(other.views(0).cedd(), cut.views(0).cedd()) << name;
  }
}

// After each enrollment the operator is told how sure the accept / unknown rule can be with the
// objects now enrolled (cli/rule_estimate_text.h); `orbit info` says the same.
TEST(EnrollCommandTest, SaysHowSureTheAcceptUnknownRuleIsWithTheObjectsEnrolled) {
  ServerProcess server;
  const std::string eth = (testing::DataDir() / "eth-80-dev").string();
  const auto enroll = [&](const std::string& object) {
    const std::string views = " --image " + eth + "/images/" + object + "-090-000.jpg" +
                              " --azimuth 0 --image " + eth + "/images/" + object +
                              "-090-090.jpg --azimuth 90 --image " + eth + "/images/" + object +
                              "-090-180.jpg --azimuth 180 --boxes " + eth + "/boxes.csv";
    const auto r = RunOrbit("enroll --server " + server.address() + " --name " + object + views);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  // One object: nothing can play an unknown one yet.
  EXPECT_THAT(enroll("apple1"), HasSubstr("accept / unknown  not calibrated: it needs two objects "
                                          "enrolled; until then every answer is undecided\n"));
  // Two: calibrated on both, with the warning that two objects are few.
  const std::string second = enroll("cup1");
  EXPECT_THAT(second, HasSubstr("accept / unknown  calibrated on 2 objects: of windows of 8 "
                                "frames, accepts about "));
  EXPECT_THAT(second, HasSubstr("  few objects: on objects nobody enrolled the rate can stray"));
  const auto info = RunOrbit("info --server " + server.address());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("accept / unknown  calibrated on 2 objects: "));
  const auto json = RunOrbit("info --json --server " + server.address());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto estimate = nlohmann::json::parse(json.out)["rule_estimate"];
  EXPECT_EQ(estimate["objects"], 2);
  EXPECT_EQ(estimate["frames"], 8);
  // Every known window the default target (0.15) accepts is one the rule's own estimate counts: the
  // shares are shares.
  EXPECT_GT(estimate["known_accepted"].get<double>(), 0.5);
  EXPECT_LE(estimate["known_accepted"].get<double>(), 1.0);
  EXPECT_LE(estimate["unknown_accepted"].get<double>(), 0.15 + 1.0 / 2000);
}

TEST(EnrollCommandTest, ABadBoxIsRefusedNamingTheFlagOrTheLineAndNothingIsEnrolled) {
  ServerProcess server;
  const ScratchDir dir;
  const AppleViews apple;
  const std::string at = "enroll --server " + server.address() + " --name apple";
  const std::string front = " --image " + apple.front + " --azimuth 0";
  const std::string side = " --image " + apple.side + " --azimuth 45";
  const auto refused = [&](const std::string& arguments, int exit_code = 1) {
    const auto r = RunOrbit(at + arguments);
    EXPECT_EQ(r.exit_code, exit_code) << arguments << "\n" << r.out;
    return r.err;
  };
  // The first image's box is good, the second's is not: neither is enrolled.
  EXPECT_THAT(refused(front + " --box 32,32,192,191" + side + " --box 10,10,300,20"),
              HasSubstr("--box 10,10,300,20 for " + apple.side +
                        ": x+w must be at most the image's width 256"));
  EXPECT_THAT(refused(front + " --box 10,250,20,7"),
              HasSubstr("--box 10,250,20,7 for " + apple.front +
                        ": y+h must be at most the image's height 256"));
  EXPECT_THAT(refused(front + " --box 10,10,300"),
              HasSubstr("--box '10,10,300' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)"));
  EXPECT_THAT(refused(front + " --box 10,10,0,20"),
              HasSubstr("--box '10,10,0,20' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)"));
  EXPECT_THAT(refused(front + side + " --box 32,32,192,191"),
              HasSubstr("give one --box per --image (2 images, 1 boxes)"));
  const std::string boxes =
      dir.Write("boxes.csv", "path,x,y,w,h\n" + apple.front + ",32,32,192,191\n" + apple.side +
                                 ",200,31,196,193\n")
          .string();
  EXPECT_THAT(refused(front + side + " --boxes " + boxes),
              HasSubstr(boxes + ":3: x+w must be at most the image's width 256"));
  const std::string one =
      dir.Write("one.csv", "path,x,y,w,h\n" + apple.front + ",32,32,192,191\n").string();
  EXPECT_THAT(refused(front + side + " --boxes " + one), HasSubstr("no box for " + apple.side));
  // Flags CLI11 refuses as they are parsed (exit code 2): a margin out of range, both ways of
  // giving boxes.
  EXPECT_THAT(refused(front + " --box 32,32,192,191 --box-margin 1.5", 2),
              HasSubstr("--box-margin"));
  EXPECT_THAT(refused(front + " --box 32,32,192,191 --boxes " + one, 2), HasSubstr("--box"));

  const auto info = RunOrbit("info --json --server " + server.address());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["objects"], 0);
}

}  // namespace
}  // namespace orbit
