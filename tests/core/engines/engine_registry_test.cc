// The engines by name (core/engines/engine_registry.h): one list, every engine made from it,
// unknown names refused with the list.
#include "core/engines/engine_registry.h"

#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/coil_models.h"
#include "tests/support/sector_table.h"

namespace orbit {
namespace {

using testing::CoilObjects;
using ::testing::ElementsAre;
using testing::EvenView;
using testing::HoldsSectorTable;

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

}  // namespace
}  // namespace orbit
