// PrepareForSessions (server/session_engine.h): what a session's first frame on a new snapshot
// would build for every session after it is built by the writer, before sessions see it.
#include "server/session_engine.h"

#include <memory>

#include <gtest/gtest.h>

#include "api/engines/engine_names.h"
#include "tests/support/coil_models.h"
#include "tests/support/sector_table.h"

namespace orbit::server {
namespace {

using testing::CoilObjects;
using testing::EvenView;
using testing::HoldsSectorTable;

TEST(SessionEngineTest, TheWriterPreparesTheHmmsSectorTableBeforeSessionsSeeTheSnapshot) {
  const SessionSettings product;  // the HMM (core/engines/product_pipeline.h)
  ASSERT_TRUE(RunsHmm(product.engine));
  const int states = product.options.hmm_states;
  ViewIndex index(CoilObjects(1, 3, EvenView));
  index.PrepareSnapshotsWith(PrepareForSessions(product));
  const auto before = index.Snapshot();
  EXPECT_FALSE(HoldsSectorTable(*before, states));  // built before preparations were asked for

  index.Add(CoilObjects(4, 4, EvenView).front());
  const auto after = index.Snapshot();
  EXPECT_TRUE(HoldsSectorTable(*after, states));
  EXPECT_EQ(SectorSimilarityTable::Of(*after, states)->object_count(), 4u);
  EXPECT_EQ(after->ChangeSince(*before)->added.size(), 1u);

  // Sessions without an HMM use no sector table: none is built for them.
  SessionSettings vci;
  vci.engine = ParseSessionEngine("vci");
  ViewIndex other(CoilObjects(1, 2, EvenView));
  other.PrepareSnapshotsWith(PrepareForSessions(vci));
  other.Remove(2);
  EXPECT_FALSE(HoldsSectorTable(*other.Snapshot(), states));
}

}  // namespace
}  // namespace orbit::server
