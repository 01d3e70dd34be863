// The hot loops' two paths (core/base/cpu_dispatch.h) give bit-identical results: every
// descriptor variant and noise estimate of the CEDD conformance images and of real photographs,
// the view index's similarities and every engine's updates on COIL-100's LIRE descriptors, each
// computed on the portable path and on the fastest path of this CPU and compared exactly.
#include "core/base/cpu_dispatch.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/noise_estimate.h"
#include "core/engines/engine_registry.h"
#include "core/index/view_index.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::DataDir;

// A double written exactly (hexadecimal significand), so that equal text means equal bits.
std::string Exact(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

// " object:view=value", the value written exactly.
std::string Scored(std::int64_t object, int view, double value) {
  char text[96];
  std::snprintf(text, sizeof text, " %lld:%d=%a", static_cast<long long>(object), view, value);
  return text;
}

std::string Values(const DescriptorValues& values) {
  std::string text;
  for (const std::uint8_t value : values) text += static_cast<char>('0' + value);
  return text;
}

// compute() on the portable path, then on the fastest; the fastest stays active afterwards.
template <typename Compute>
std::pair<std::vector<std::string>, std::vector<std::string>> OnBothPaths(Compute compute) {
  TEST_SetHotLoopPath(HotLoopPath::kPortable);
  std::vector<std::string> portable = compute();
  TEST_SetHotLoopPath(HotLoopPath::kFastest);
  std::vector<std::string> fastest = compute();
  return {portable, fastest};
}

void ExpectEqualLines(const std::vector<std::string>& portable,
                      const std::vector<std::string>& fastest) {
  ASSERT_EQ(portable.size(), fastest.size());
  for (std::size_t i = 0; i < portable.size(); ++i) {
    EXPECT_EQ(portable[i], fastest[i]) << "line " << i << " differs between the paths";
  }
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

// COIL-100's LIRE descriptors: the views at even multiples of 5 degrees are the models, walks
// over the others are the queries.
TEST(HotLoopPathTest, SearchesAndEveryEngineAreBitIdenticalOnBothPaths) {
  std::vector<ObjectModel> models(100);
  std::vector<std::vector<ModelView>> queries(100);
  for (const auto& reference :
       testing::ReadReferenceVectors(DataDir() / "coil-100-lire-cedd.txt")) {
    int object = 0, azimuth = 0;
    ASSERT_EQ(std::sscanf(reference.path.c_str(), "coil-100/obj%d__%d.png", &object, &azimuth), 2)
        << reference.path;
    ModelView view;
    view.descriptor = reference.values;
    view.azimuth = azimuth;
    (azimuth % 10 == 0 ? models[object - 1].views : queries[object - 1]).push_back(view);
  }
  for (int o = 0; o < 100; ++o) {
    models[o].id = o + 1;
    models[o].name = "obj" + std::to_string(o + 1);
  }

  const auto [portable, fastest] = OnBothPaths([&] {
    std::vector<std::string> lines;
    ViewIndex index(models, {.search = SearchMode::kExact});
    const auto snapshot = index.Snapshot();
    for (const int object : {3, 27, 64, 91}) {
      for (const ModelView& query : queries[object - 1]) {
        std::string text = "search " + std::to_string(object);
        for (const ViewMatch& match : snapshot->SearchExact(query.descriptor, 10)) {
          text += Scored(match.object, match.view, match.similarity);
        }
        lines.push_back(text);
      }
    }
    for (const std::string_view engine_name : EngineNames()) {
      const EngineOptions options;
      PrepareSnapshot(engine_name, options, *snapshot);
      for (const int object : {3, 27, 64, 91}) {
        auto engine = CreateEngine(engine_name, options);
        for (const ModelView& query : queries[object - 1]) {
          const FrameUpdate update = engine->Observe(
              snapshot, {{DescriptorVariant::kCeddLire, query.descriptor}, query.azimuth});
          std::string text = std::string(engine_name) + " " + std::to_string(object) + " " +
                             std::to_string(static_cast<int>(update.decision)) + " " +
                             Exact(update.confidence) + " " + Exact(update.unknown_statistic);
          for (const RankedObject& ranked : update.ranking) {
            text += Scored(ranked.object, 0, ranked.score);
          }
          lines.push_back(text);
        }
      }
    }
    return lines;
  });
  EXPECT_EQ(portable.size(), 4u * 36 * (1 + EngineNames().size()));
  ExpectEqualLines(portable, fastest);
}

}  // namespace
}  // namespace orbit
