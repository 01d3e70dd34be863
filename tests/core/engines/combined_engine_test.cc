// vci-hmm (core/engines/combined_engine.h): each object scored by the mean of VCI's and the HMM's
// scores, each ranking kCombinedDepth deep; the judgement of the engine whose top-1 wins.
#include "core/engines/combined_engine.h"

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"
#include "tests/support/coil_models.h"

namespace orbit {
namespace {

using testing::CoilObjects;
using testing::CoilView;
using testing::EvenView;

std::vector<QueryFrame> Frames(int object, const std::vector<int>& azimuths) {
  std::vector<QueryFrame> frames;
  for (int azimuth : azimuths) {
    frames.push_back(
        {{DescriptorVariant::kCeddLire, CoilView(object, azimuth)}, static_cast<double>(azimuth)});
  }
  return frames;
}

TEST(CombinedEngineTest, ScoresAreTheMeanOfVciAndHmmAndTheJudgementIsTheWinnersEngines) {
  ViewIndex index(CoilObjects(1, 40, EvenView));
  const EngineOptions options{.top_k = 3};
  EngineOptions deep = options;
  deep.top_k = kCombinedDepth;
  const auto combined = CreateEngine("vci-hmm", options);
  const auto vci = CreateEngine("vci", deep);
  const auto hmm = CreateEngine("hmm", deep);
  EXPECT_EQ(combined->name(), "vci-hmm");
  EXPECT_EQ(combined->options().top_k, 3);
  for (int object : {3, 17, 33}) {
    const std::vector<QueryFrame> frames = Frames(object, {15, 25, 35, 45});
    const FrameUpdate both = combined->ObserveSequence(index.Snapshot(), frames);
    const FrameUpdate v = vci->ObserveSequence(index.Snapshot(), frames);
    const FrameUpdate h = hmm->ObserveSequence(index.Snapshot(), frames);
    std::map<ObjectId, double> sum;
    for (const RankedObject& r : v.ranking) sum[r.object] += r.score;
    for (const RankedObject& r : h.ranking) sum[r.object] += r.score;
    ASSERT_EQ(both.ranking.size(), 3u);
    EXPECT_EQ(both.ranking[0].object, object);
    for (const RankedObject& r : both.ranking) {
      EXPECT_DOUBLE_EQ(r.score, sum[r.object] / 2) << "object " << r.object;
    }
    // Both engines put the object first here: the judgement is VCI's, the move VCI's.
    ASSERT_EQ(v.ranking[0].object, object);
    EXPECT_EQ(both.decision, v.decision);
    EXPECT_DOUBLE_EQ(both.unknown_statistic, v.unknown_statistic);
    EXPECT_DOUBLE_EQ(both.confidence, v.confidence);
    EXPECT_EQ(both.move, v.move);
    EXPECT_EQ(both.frame_index, 3);
  }
}

TEST(CombinedEngineTest, FramesOneByOneEqualTheBatchAndResetStartsOver) {
  ViewIndex index(CoilObjects(1, 10, EvenView));
  const auto engine = CreateEngine("vci-hmm", {.window = 3});
  const std::vector<QueryFrame> frames = Frames(7, {95, 105, 115, 125, 135});
  FrameUpdate last;
  for (const QueryFrame& frame : frames) last = engine->Observe(index.Snapshot(), frame);
  const FrameUpdate batch =
      CreateEngine("vci-hmm", {.window = 3})->ObserveSequence(index.Snapshot(), frames);
  EXPECT_EQ(last.frame_index, 4);
  EXPECT_EQ(batch.frame_index, 4);
  ASSERT_EQ(last.ranking.size(), batch.ranking.size());
  for (std::size_t i = 0; i < last.ranking.size(); ++i) {
    EXPECT_EQ(last.ranking[i].object, batch.ranking[i].object);
    EXPECT_DOUBLE_EQ(last.ranking[i].score, batch.ranking[i].score);
  }
  engine->Reset();
  EXPECT_EQ(engine->Observe(index.Snapshot(), frames[0]).frame_index, 0);
}

TEST(CombinedEngineTest, ABadFrameChangesNeitherEngine) {
  ViewIndex index(CoilObjects(1, 5, EvenView));
  const auto engine = CreateEngine("vci-hmm");
  engine->Observe(index.Snapshot(), Frames(2, {20})[0]);
  QueryFrame bad = Frames(2, {30})[0];
  bad.blur = 2;
  EXPECT_THROW(engine->Observe(index.Snapshot(), bad), std::invalid_argument);
  EXPECT_EQ(engine->Observe(index.Snapshot(), Frames(2, {30})[0]).frame_index, 1);
}

}  // namespace
}  // namespace orbit
