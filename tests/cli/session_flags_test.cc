// The session flags of `orbit recognize` and `orbit loadtest` reach the session's options.
#include "cli/session_flags.h"

#include <gtest/gtest.h>

namespace orbit::cli {
namespace {

RecognitionOptions Parse(std::vector<std::string> arguments) {
  CLI::App app;
  SessionFlags flags;
  AddSessionFlags(app, flags);
  arguments.insert(arguments.begin(), "orbit");
  std::vector<const char*> argv;
  for (const std::string& a : arguments) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return ToRecognitionOptions(flags);
}

TEST(SessionFlagsTest, LeftOutFlagsTakeTheServersDefaults) {
  const RecognitionOptions options = Parse({});
  EXPECT_EQ(options.rejection, v1::REJECTION_UNSPECIFIED);
  EXPECT_FALSE(options.false_accept_rate.has_value());
  EXPECT_FALSE(options.known_accept_rate.has_value());
  EXPECT_FALSE(options.threshold.has_value());
}

TEST(SessionFlagsTest, TheRejectionRuleAndItsTargetReachTheSession) {
  const RecognitionOptions calibrated = Parse(
      {"--rejection", "calibrated", "--false-accept-rate", "0.02", "--known-accept-rate", "0"});
  EXPECT_EQ(calibrated.rejection, v1::REJECTION_CALIBRATED);
  EXPECT_EQ(calibrated.false_accept_rate, 0.02);
  EXPECT_EQ(calibrated.known_accept_rate, 0.0);
  const RecognitionOptions th = Parse({"--rejection", "th", "--threshold", "1.5"});
  EXPECT_EQ(th.rejection, v1::REJECTION_TH);
  EXPECT_EQ(th.threshold, 1.5);
  EXPECT_THROW(Parse({"--rejection", "strict"}), CLI::ValidationError);
  EXPECT_THROW(Parse({"--false-accept-rate", "1"}), CLI::ValidationError);
  EXPECT_THROW(Parse({"--known-accept-rate", "1"}), CLI::ValidationError);
  EXPECT_THROW(Parse({"--known-accept-rate", "-0.1"}), CLI::ValidationError);
}

}  // namespace
}  // namespace orbit::cli
