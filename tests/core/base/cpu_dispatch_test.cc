// The hot loops' two paths (core/base/cpu_dispatch.h) give bit-identical results: every
// descriptor variant and noise estimate of the CEDD conformance images and of real photographs,
// computed on the portable path and on the fastest path of this CPU and compared exactly. The
// view index's similarities and the engines' updates, the server's hot loops, are compared in
// tests/core/engines/engine_registry_test.cc.
#include "core/base/cpu_dispatch.h"

#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/noise_estimate.h"
#include "tests/support/hot_loop_paths.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::DataDir;
using testing::Exact;
using testing::ExpectEqualLines;
using testing::OnBothPaths;

std::string Values(const DescriptorValues& values) {
  std::string text;
  for (const std::uint8_t value : values) text += static_cast<char>('0' + value);
  return text;
}

TEST(HotLoopPathTest, TheFastestPathIsActiveUntilATestChoosesThePortableOne) {
  EXPECT_EQ(ActiveHotLoopPath(), HotLoopPath::kFastest);
  TEST_SetHotLoopPath(HotLoopPath::kPortable);
  EXPECT_EQ(ActiveHotLoopPath(), HotLoopPath::kPortable);
  TEST_SetHotLoopPath(HotLoopPath::kFastest);
  EXPECT_EQ(ActiveHotLoopPath(), HotLoopPath::kFastest);
}

// The conformance set exercises every size and grid mode of the CEDD reference; its photos
// (1024 pixels across) and the car photographs exercise the canonical frame's block means and
// blur on real images. Every variant reads every hot loop of the descriptor.
TEST(HotLoopPathTest, DescriptorsAreBitIdenticalOnBothPaths) {
  std::vector<std::string> files;
  const auto conformance = DataDir() / "cedd-conformance";
  for (const auto& reference :
       testing::ReadReferenceVectors(conformance / "lire-cedd-reference.txt")) {
    files.push_back((conformance / reference.path).string());
  }
  ASSERT_EQ(files.size(), 66u);
  std::ifstream manifest(DataDir() / "epfl-cars" / "manifest.csv");
  std::string line;
  std::getline(manifest, line);  // header
  for (int row = 0; std::getline(manifest, line); ++row) {
    if (row % 50 == 0)
      files.push_back((DataDir() / "epfl-cars" / line.substr(0, line.find(','))).string());
  }
  ASSERT_GT(files.size(), 80u);

  const auto [portable, fastest] = OnBothPaths([&] {
    std::vector<std::string> lines;
    for (const std::string& file : files) {
      const cv::Mat image = ReadImageFile(file);
      for (const DescriptorVariant variant : kDescriptorVariants) {
        lines.push_back(file + " " + std::string(VariantName(variant)) + " " +
                        Values(ExtractCedd(image, variant).values));
      }
      lines.push_back(file + " noise " + Exact(EstimateNoiseSigma(image)));
    }
    return lines;
  });
  ExpectEqualLines(portable, fastest);
}

}  // namespace
}  // namespace orbit
