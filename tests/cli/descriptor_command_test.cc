// `orbit descriptor` as a user runs it: output format, variants, errors, help.
#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::DataDir;
using testing::OrbitBinary;
using testing::RunCommand;

// The reference line for a COIL-100 image, with its path as given on the command line.
std::string ReferenceLine(const std::string& relative, const std::string& shown_path) {
  for (const auto& ref : testing::ReadReferenceVectors(DataDir() / "coil-100-lire-cedd.txt")) {
    if (ref.path == relative) {
      std::string line = shown_path;
      for (auto v : DescriptorBytes(ref.values, DescriptorVariant::kCeddLire)) {
        line += ' ';
        line += static_cast<char>('0' + v);
      }
      return line;
    }
  }
  return "";
}

TEST(CliDescriptor, PrintsOneLinePerImageAndReportsUnreadableFiles) {
  const std::string a = (DataDir() / "coil-100/obj1__0.png").string();
  const std::string b = (DataDir() / "coil-100/obj42__90.png").string();
  const auto result =
      RunCommand(OrbitBinary() + " descriptor " + a + " /nonexistent/missing.png " + b);
  EXPECT_EQ(result.exit_code, 1);
  const auto lines = testing::OutputLines(result.out);
  ASSERT_EQ(lines.size(), 2u) << result.out;
  EXPECT_EQ(lines[0], ReferenceLine("coil-100/obj1__0.png", a));
  EXPECT_EQ(lines[1], ReferenceLine("coil-100/obj42__90.png", b));
  EXPECT_NE(result.err.find("/nonexistent/missing.png"), std::string::npos) << result.err;
}

TEST(CliDescriptor, NotAnImageIsAnErrorToo) {
  const auto result =
      RunCommand(OrbitBinary() + " descriptor " + (DataDir() / "coil-100-lire-cedd.txt").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_TRUE(result.out.empty());
  EXPECT_NE(result.err.find("coil-100-lire-cedd.txt"), std::string::npos) << result.err;
}

TEST(CliDescriptor, VariantsDifferWhereLireIgnoresPixels) {
  const std::string file =
      (DataDir() / "cedd-conformance/synth/coil_like_128_outside80_modified.png").string();
  const auto lire = RunCommand(OrbitBinary() + " descriptor --variant cedd-lire " + file);
  const auto full = RunCommand(OrbitBinary() + " descriptor --variant cedd-full " + file);
  EXPECT_EQ(lire.exit_code, 0);
  EXPECT_EQ(full.exit_code, 0);
  EXPECT_EQ(testing::OutputLines(lire.out).size(), 1u);
  EXPECT_EQ(testing::OutputLines(full.out).size(), 1u);
  EXPECT_NE(lire.out, full.out);
}

TEST(CliDescriptor, RefusesAnUnknownVariant) {
  const auto result = RunCommand(OrbitBinary() + " descriptor --variant sift " +
                                 (DataDir() / "coil-100/obj1__0.png").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("sift"), std::string::npos) << result.err;
}

TEST(CliHelp, ExplainsTheToolAndTheSubcommand) {
  const auto top = RunCommand(OrbitBinary() + " --help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("descriptor"), std::string::npos) << top.out;
  const auto sub = RunCommand(OrbitBinary() + " descriptor --help");
  EXPECT_EQ(sub.exit_code, 0);
  EXPECT_NE(sub.out.find("--variant"), std::string::npos) << sub.out;
  EXPECT_NE(sub.out.find("cedd-full"), std::string::npos) << sub.out;
  const auto none = RunCommand(OrbitBinary());
  EXPECT_NE(none.exit_code, 0);
}

}  // namespace
}  // namespace orbit
