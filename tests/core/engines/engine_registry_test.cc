// The engines by name (core/engines/engine_registry.h): one list, every engine made from it,
// unknown names refused with the list; and every engine's updates, with the view index's
// searches, bit-identical on both paths of the hot loops (core/base/cpu_dispatch.h).
#include "core/engines/engine_registry.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/index/view_index.h"
#include "tests/support/coil_models.h"
#include "tests/support/hot_loop_paths.h"
#include "tests/support/sector_table.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilObjects;
using testing::DataDir;
using ::testing::ElementsAre;
using testing::EvenView;
using testing::Exact;
using testing::ExpectEqualLines;
using testing::HoldsSectorTable;
using testing::OnBothPaths;

// " object:view=value", the value written exactly.
std::string Scored(std::int64_t object, int view, double value) {
  char text[96];
  std::snprintf(text, sizeof text, " %lld:%d=%a", static_cast<long long>(object), view, value);
  return text;
}

TEST(EngineRegistryTest, NamesTheEightEnginesInOrder) {
  EXPECT_THAT(EngineNames(),
              ElementsAre("eis", "siis", "eiis", "vci-bm", "vci-w0", "vci", "hmm", "vci-hmm"));
  for (const EngineKind& kind : EngineKinds()) {
    EXPECT_FALSE(kind.summary.empty()) << kind.name;
    EXPECT_EQ(kind.keeps_hmm, kind.name == "hmm" || kind.name == "vci-hmm") << kind.name;
  }
}

TEST(EngineRegistryTest, CreatesEveryEngineByNameAndChecksOptions) {
  ASSERT_EQ(EngineNames().size(), 8u);
  for (const std::string_view name : EngineNames()) EXPECT_EQ(CreateEngine(name)->name(), name);
  EXPECT_THROW(CreateEngine("vci-x"), std::invalid_argument);
  EXPECT_THROW(CreateEngine("vci", {.window = 0}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("vci", {.window = 65}), std::invalid_argument);
  EXPECT_NO_THROW(CreateEngine("vci", {.window = 64}));
  EXPECT_THROW(CreateEngine("hmm", {.hmm_states = 0}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("eis", {.threshold = 0}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("vci", {.orientation_weight = -1}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("vci", {.orientation_weight = 1001}), std::invalid_argument);
  EXPECT_NO_THROW(CreateEngine("vci", {.orientation_weight = 1000}));
  EXPECT_THROW(CreateEngine("vci", {.list_length = 0}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("hmm", {.nearest_view_weight = -0.1}), std::invalid_argument);
  EXPECT_THROW(CreateEngine("hmm", {.nearest_view_weight = 1.1}), std::invalid_argument);
  EXPECT_NO_THROW(CreateEngine("hmm", {.nearest_view_weight = 1}));
}

TEST(EngineRegistryTest, AnUnknownNameIsRefusedListingTheEngines) {
  try {
    CreateEngine("vci+hmm");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown engine \"vci+hmm\" (known: eis, siis, eiis, vci-bm, vci-w0, vci, hmm, "
              "vci-hmm)");
  }
}

TEST(EngineRegistryTest, PreparingASnapshotBuildsTheSectorTableOnlyForEnginesWithAnHmm) {
  const EngineOptions options{.hmm_states = 6};
  ViewIndex index(CoilObjects(1, 3, EvenView));
  PrepareSnapshot("vci", options, *index.Snapshot());
  EXPECT_FALSE(HoldsSectorTable(*index.Snapshot(), 6));
  PrepareSnapshot("vci-hmm", options, *index.Snapshot());
  EXPECT_TRUE(HoldsSectorTable(*index.Snapshot(), 6));
  EXPECT_FALSE(HoldsSectorTable(*index.Snapshot(), 8));
}

// COIL-100's LIRE descriptors: the views at even multiples of 5 degrees are the models, walks
// over the others are the queries. View searches, object candidates (scanned and from the
// summary graph) and every engine's updates.
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
    // Object candidates from the summaries: scanned (exact) and from the summary graph.
    ViewIndex graph(models, {.search = SearchMode::kKdTree});
    for (const auto& candidates_of : {snapshot, graph.Snapshot()}) {
      for (const int object : {3, 27, 64, 91}) {
        for (const ModelView& query : queries[object - 1]) {
          std::string text = "candidates " + std::to_string(object);
          for (const ObjectCandidate& c : candidates_of->ObjectCandidates(query.descriptor, 8)) {
            text += Scored(static_cast<std::int64_t>(c.position), 0, c.similarity);
          }
          lines.push_back(text);
        }
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
  EXPECT_EQ(portable.size(), 4u * 36 * (3 + EngineNames().size()));
  ExpectEqualLines(portable, fastest);
}

}  // namespace
}  // namespace orbit
