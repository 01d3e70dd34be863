#include "core/engines/candidate_hmm.h"

#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"
#include "core/engines/orientation_hmm.h"
#include "core/index/view_index.h"
#include "tests/support/coil_models.h"

namespace orbit {
namespace {

// Walks of a few COIL-100 objects, 10 degrees apart between the model's views.
std::vector<QueryFrame> Walks(std::initializer_list<int> objects) {
  std::vector<QueryFrame> frames;
  for (const int object : objects) {
    for (int azimuth = 5; azimuth < 120; azimuth += 10) {
      frames.push_back({{DescriptorVariant::kCeddLire, testing::CoilView(object, azimuth)},
                        static_cast<double>(azimuth)});
    }
  }
  return frames;
}

// With exact candidates (a kExact index), the HMM over 16 candidates of 100 objects ranks the
// window's top 5 as the HMM over every object does, scores to the last bit: both compute the
// same emissions, and the objects that rank are among every frame's 16 most similar summaries.
TEST(CandidateHmmTest, ExactCandidatesGiveTheEveryObjectHmmsTopFive) {
  ViewIndex index(testing::CoilObjects(1, 100, testing::EvenView), {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  auto candidates =
      CreateEngine("hmm", {.top_k = 5, .candidate_objects = 16, .candidates_above = 16});
  auto every = CreateEngine("hmm", {.top_k = 5});
  const std::vector<QueryFrame> frames = Walks({7, 42, 93});
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const FrameUpdate some = candidates->Observe(snapshot, frames[f]);
    const FrameUpdate all = every->Observe(snapshot, frames[f]);
    ASSERT_EQ(some.ranking.size(), 5u);
    for (std::size_t r = 0; r < 5; ++r) {
      EXPECT_EQ(some.ranking[r].object, all.ranking[r].object) << "frame " << f << ", rank " << r;
      EXPECT_EQ(some.ranking[r].score, all.ranking[r].score) << "frame " << f << ", rank " << r;
    }
    EXPECT_EQ(some.decision, all.decision) << "frame " << f;
    EXPECT_EQ(some.frame_index, static_cast<std::int64_t>(f));
  }
}

// The product's options with the kd-tree's approximate candidates: the top object of every
// update is the every-object HMM's.
TEST(CandidateHmmTest, KdTreeCandidatesKeepTheProductsTopObject) {
  ViewIndex index(testing::CoilObjects(1, 100, testing::EvenView), {.search = SearchMode::kKdTree});
  const auto snapshot = index.Snapshot();
  EngineOptions options = {.top_k = 5, .nearest_view_weight = 0.5};
  options.hmm_sharpness = kMaxHmmSharpness;
  auto every = CreateEngine("hmm", options);
  options.candidate_objects = 32;
  options.candidates_above = 32;
  auto candidates = CreateEngine("hmm", options);
  const std::vector<QueryFrame> frames = Walks({3, 18, 55, 77, 100});
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const FrameUpdate some = candidates->Observe(snapshot, frames[f]);
    const FrameUpdate all = every->Observe(snapshot, frames[f]);
    ASSERT_FALSE(some.ranking.empty());
    EXPECT_EQ(some.ranking[0].object, all.ranking[0].object) << "frame " << f;
    EXPECT_EQ(some.ranking[0].score, all.ranking[0].score) << "frame " << f;
  }
}

// A session whose catalogue grows past candidates_above mid-walk answers from then on as a fresh
// session of the HMM over candidates given the same window, and as the HMM over every object
// once it shrinks back; its frame count runs on across both switches.
TEST(CandidateHmmTest, ASessionSwitchesEnginesAsItsCatalogueCrossesTheLimit) {
  ViewIndex index(testing::CoilObjects(1, 10, testing::EvenView), {.search = SearchMode::kExact});
  const EngineOptions options = {.top_k = 5, .candidate_objects = 12, .candidates_above = 12};
  auto session = CreateEngine("hmm", options);
  const std::vector<QueryFrame> frames = Walks({4, 9});
  std::vector<QueryFrame> window;
  const auto observe = [&](std::size_t f) {
    window.push_back(frames[f]);
    if (window.size() > static_cast<std::size_t>(options.window)) window.erase(window.begin());
    return session->Observe(index.Snapshot(), frames[f]);
  };
  for (std::size_t f = 0; f < 6; ++f) observe(f);
  for (const ObjectModel& model : testing::CoilObjects(11, 30, testing::EvenView)) {
    index.Add(model);
  }
  const auto large = index.Snapshot();
  const FrameUpdate switched = observe(6);
  const FrameUpdate fresh = CreateEngine("hmm", options)->ObserveSequence(large, window);
  EngineOptions every_object = options;
  every_object.candidate_objects = 0;
  ASSERT_EQ(switched.ranking.size(), fresh.ranking.size());
  for (std::size_t r = 0; r < fresh.ranking.size(); ++r) {
    EXPECT_EQ(switched.ranking[r].object, fresh.ranking[r].object) << "rank " << r;
    EXPECT_EQ(switched.ranking[r].score, fresh.ranking[r].score) << "rank " << r;
  }
  EXPECT_EQ(switched.frame_index, 6);
  for (int id = 11; id <= 30; ++id) index.Remove(id);
  const FrameUpdate back = observe(7);
  const FrameUpdate plain =
      CreateEngine("hmm", every_object)->ObserveSequence(index.Snapshot(), window);
  ASSERT_EQ(back.ranking.size(), plain.ranking.size());
  for (std::size_t r = 0; r < plain.ranking.size(); ++r) {
    EXPECT_EQ(back.ranking[r].object, plain.ranking[r].object) << "rank " << r;
    EXPECT_EQ(back.ranking[r].score, plain.ranking[r].score) << "rank " << r;
  }
  EXPECT_EQ(back.frame_index, 7);
  EXPECT_EQ(back.ranking[0].object, 4);
}

// Object 42 is enrolled after six frames of it: the session answers it from the next frame on,
// as a fresh session on the same window does, even when that frame (one of object 3) does not
// propose it: the window's frames that would have proposed it take it as their candidate.
TEST(CandidateHmmTest, AnObjectEnrolledMidWalkIsAnsweredFromTheNextFrame) {
  ViewIndex index(testing::CoilObjects(1, 40, testing::EvenView), {.search = SearchMode::kExact});
  const EngineOptions options = {.top_k = 5, .candidate_objects = 8, .candidates_above = 8};
  auto session = CreateEngine("hmm", options);
  std::vector<QueryFrame> window = Walks({42});
  window.resize(6);
  for (const QueryFrame& frame : window) session->Observe(index.Snapshot(), frame);
  index.Add(testing::CoilObjects(42, 42, testing::EvenView).front());
  const QueryFrame other{{DescriptorVariant::kCeddLire, testing::CoilView(3, 95)}, 95.0};
  ASSERT_EQ(index.Snapshot()->ObjectCandidates(other.descriptor.values, 8).size(), 8u);
  for (const ObjectCandidate& c : index.Snapshot()->ObjectCandidates(other.descriptor.values, 8)) {
    ASSERT_NE(index.Snapshot()->objects()[c.position].object->id(), 42)
        << "the test needs a last frame that does not propose object 42";
  }
  window.push_back(other);
  const FrameUpdate rebased = session->Observe(index.Snapshot(), other);
  const FrameUpdate fresh = CreateEngine("hmm", options)->ObserveSequence(index.Snapshot(), window);
  ASSERT_FALSE(rebased.ranking.empty());
  EXPECT_EQ(rebased.ranking[0].object, 42);
  EXPECT_EQ(rebased.ranking[0].score, fresh.ranking[0].score);
  EXPECT_EQ(rebased.frame_index, 6);
}

// Object 7 is deleted while the window holds seven frames of it: from the next frame no answer
// names it, and the top object is a fresh session's on the same window, score to the last bit.
TEST(CandidateHmmTest, AnObjectDeletedMidWalkLeavesTheAnswerAtTheNextFrame) {
  ViewIndex index(testing::CoilObjects(1, 40, testing::EvenView), {.search = SearchMode::kExact});
  const EngineOptions options = {.top_k = 5, .candidate_objects = 8, .candidates_above = 8};
  auto session = CreateEngine("hmm", options);
  const std::vector<QueryFrame> walk = Walks({7});
  std::vector<QueryFrame> window(walk.begin(), walk.begin() + 7);
  FrameUpdate before;
  for (const QueryFrame& frame : window) before = session->Observe(index.Snapshot(), frame);
  ASSERT_EQ(before.ranking[0].object, 7);
  index.Remove(7);
  window.push_back(walk[7]);
  const FrameUpdate rebased = session->Observe(index.Snapshot(), walk[7]);
  const FrameUpdate fresh = CreateEngine("hmm", options)->ObserveSequence(index.Snapshot(), window);
  ASSERT_FALSE(rebased.ranking.empty());
  for (const RankedObject& ranked : rebased.ranking) EXPECT_NE(ranked.object, 7);
  EXPECT_EQ(rebased.ranking[0].object, fresh.ranking[0].object);
  EXPECT_EQ(rebased.ranking[0].score, fresh.ranking[0].score);
}

}  // namespace
}  // namespace orbit
