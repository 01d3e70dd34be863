#include "core/engines/recognition_engine.h"

#include "core/engines/engine_registry.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/similarity.h"
#include "core/descriptor/view_description.h"
#include "core/index/indexed_object.h"
#include "core/index/similarity_rows.h"
#include "core/index/view_index.h"
#include "tests/support/coil_models.h"

namespace orbit {
namespace {

using testing::CoilObject;
using testing::CoilObjects;
using testing::CoilView;
using testing::EvenView;

// Frames of COIL object `object` from the views at true azimuths `azimuths` (odd multiples of
// 5, which the even/odd split keeps out of the model), each reported by the device at
// true azimuth + offset + a small irregular sensor error.
std::vector<QueryFrame> Frames(int object, const std::vector<int>& azimuths, double offset) {
  static constexpr double kSensorError[] = {0.7, -1.3, 2.1, -0.4, 1.6, -2.2, 0.9, -0.8};
  std::vector<QueryFrame> frames;
  for (std::size_t k = 0; k < azimuths.size(); ++k) {
    frames.push_back({{DescriptorVariant::kCeddLire, CoilView(object, azimuths[k] % 360)},
                      azimuths[k] + offset + kSensorError[k % 8]});
  }
  return frames;
}

DescriptorValues Bins(std::initializer_list<std::pair<int, int>> bins) {
  DescriptorValues values{};
  for (const auto& [bin, value] : bins) values[bin] = static_cast<std::uint8_t>(value);
  return values;
}

ModelView View(const DescriptorValues& values, double azimuth) {
  ModelView view;
  view.descriptor = values;
  view.azimuth = azimuth;
  return view;
}

std::shared_ptr<const ViewIndexSnapshot> CoilIndex(SearchMode mode) {
  static ViewIndex exact(CoilObjects(1, 10, EvenView), {.search = SearchMode::kExact});
  static ViewIndex kd(CoilObjects(1, 10, EvenView), {.search = SearchMode::kKdTree});
  return mode == SearchMode::kExact ? exact.Snapshot() : kd.Snapshot();
}

void ExpectSameUpdate(const FrameUpdate& a, const FrameUpdate& b, const std::string& what) {
  EXPECT_EQ(a.frame_index, b.frame_index) << what;
  ASSERT_EQ(a.ranking.size(), b.ranking.size()) << what;
  for (std::size_t i = 0; i < a.ranking.size(); ++i) {
    EXPECT_EQ(a.ranking[i].object, b.ranking[i].object) << what << " rank " << i;
    EXPECT_NEAR(a.ranking[i].score, b.ranking[i].score, 1e-9) << what << " rank " << i;
  }
  EXPECT_EQ(a.decision, b.decision) << what;
  EXPECT_EQ(a.move, b.move) << what;
}

// Every engine names the right object of ten from four frames it has never seen (views 5
// degrees from the nearest model view), with either index.
TEST(RecognitionEngineTest, EveryEngineRecognisesCoilObjectsFromUnseenViews) {
  for (const SearchMode mode : {SearchMode::kExact, SearchMode::kKdTree}) {
    for (const std::string_view name : EngineNames()) {
      const auto engine = CreateEngine(name);
      for (int object = 1; object <= 10; ++object) {
        const FrameUpdate u =
            engine->ObserveSequence(CoilIndex(mode), Frames(object, {95, 105, 115, 125}, 40));
        ASSERT_FALSE(u.ranking.empty());
        EXPECT_EQ(u.ranking[0].object, object) << name << " object " << object;
        EXPECT_EQ(u.frame_index, 3);
        for (std::size_t i = 1; i < u.ranking.size(); ++i) {
          EXPECT_GE(u.ranking[i - 1].score, u.ranking[i].score) << name;
        }
      }
    }
  }
}

// Feeding frames one by one equals the batch form, including when the window (3) slides.
TEST(RecognitionEngineTest, IncrementalFramesEqualTheBatchForm) {
  const std::vector<QueryFrame> frames = Frames(3, {205, 215, 225, 235, 245, 255}, -17);
  for (const std::string_view name : EngineNames()) {
    const auto incremental = CreateEngine(name, {.window = 3});
    FrameUpdate last;
    for (const QueryFrame& frame : frames) {
      last = incremental->Observe(CoilIndex(SearchMode::kKdTree), frame);
    }
    const auto batch = CreateEngine(name, {.window = 3});
    const FrameUpdate all = batch->ObserveSequence(CoilIndex(SearchMode::kKdTree), frames);
    EXPECT_EQ(all.frame_index, 5);
    ExpectSameUpdate(last, all, std::string(name));
    // The window holds only the last three frames: a fresh session given just those agrees
    // on everything but the frame index.
    FrameUpdate tail =
        batch->ObserveSequence(CoilIndex(SearchMode::kKdTree), std::span(frames).subspan(3));
    tail.frame_index = all.frame_index;
    ExpectSameUpdate(tail, all, std::string(name) + " tail");
  }
}

// Only azimuth differences matter: shifting every device azimuth by a constant, or letting the
// device's readings cross 0/360, changes nothing. The model side crosses 0/360 as well (true
// azimuths 335..15).
TEST(RecognitionEngineTest, ShiftedAndWrappedAzimuthsGiveIdenticalAnswers) {
  const std::vector<int> across_zero = {335, 345, 355, 365, 375};
  for (const std::string_view name : EngineNames()) {
    const auto engine = CreateEngine(name);
    const FrameUpdate reference =
        engine->ObserveSequence(CoilIndex(SearchMode::kExact), Frames(7, across_zero, 0));
    EXPECT_EQ(reference.ranking[0].object, 7) << name;
    // Device readings 335+137.25.. (no wrap), -1000.5 (negative), and 20 (crossing 360 as
    // 355, 365 -> reported 15, 25 after wrapping below).
    for (const double offset : {137.25, -1000.5, 20.0}) {
      std::vector<QueryFrame> shifted = Frames(7, across_zero, offset);
      for (QueryFrame& f : shifted) f.azimuth = std::fmod(*f.azimuth, 360.0);  // device wraps
      ExpectSameUpdate(engine->ObserveSequence(CoilIndex(SearchMode::kExact), shifted), reference,
                       std::string(name) + " offset " + std::to_string(offset));
    }
  }
}

// Any finite azimuth is valid input: 1e308 and -1e308 (whose difference overflows) act exactly
// like their equivalents 296 and 64 (core/base/angles.h), for every engine.
TEST(RecognitionEngineTest, FarApartFiniteAzimuthsActLikeTheirEquivalentsBelow360) {
  for (const std::string_view name : EngineNames()) {
    std::vector<QueryFrame> huge = Frames(7, {290, 300, 310}, 0);
    std::vector<QueryFrame> small = huge;
    huge[0].azimuth = 1e308;
    huge[1].azimuth = -1e308;
    huge[2].azimuth = 1e308;
    small[0].azimuth = 296;
    small[1].azimuth = 64;
    small[2].azimuth = 296;
    const auto engine = CreateEngine(name);
    FrameUpdate expected;
    ASSERT_NO_THROW(expected = engine->ObserveSequence(CoilIndex(SearchMode::kExact), small))
        << name;
    FrameUpdate got;
    ASSERT_NO_THROW(got = engine->ObserveSequence(CoilIndex(SearchMode::kExact), huge)) << name;
    ExpectSameUpdate(got, expected, std::string(name));
  }
}

// A sequence whose first two frames show object 2 and last three object 5: each candidate
// misses some lists and is extended there through the IMU, so the orientation-implied views
// must also depend on azimuth differences only.
TEST(RecognitionEngineTest, ListExtensionIgnoresAzimuthOffsets) {
  const auto mixed = [](double offset) {
    std::vector<QueryFrame> frames = Frames(2, {95, 105}, offset);
    for (const QueryFrame& f : Frames(5, {115, 125, 135}, offset)) frames.push_back(f);
    return frames;
  };
  for (const std::string_view name : {"vci", "vci-w0", "vci-bm"}) {
    const auto engine = CreateEngine(name, {.list_length = 2, .top_k = 10});
    const FrameUpdate reference = engine->ObserveSequence(CoilIndex(SearchMode::kExact), mixed(0));
    EXPECT_GE(reference.ranking.size(), 2u) << name;
    for (const double offset : {93.5, 250.0}) {
      ExpectSameUpdate(engine->ObserveSequence(CoilIndex(SearchMode::kExact), mixed(offset)),
                       reference, std::string(name) + " offset " + std::to_string(offset));
    }
  }
}

// VCI's list extension by hand, N_L = 1. Object 1: P at 0, Q at 90, R at 180; object 2: S at 0.
// Frame 0 is P (device 200), frame 1 is S (device 290: turned +90). L_0 = {1:P}, L_1 = {2:S}.
//   TC(S,Q) = 16/25 and TC(S,R) = 16/17 (Q = S + 3 at bin 3, R = S + 1 at bin 2); TC(P,S) = 0.
//   vci:    object 1 is extended on L_1 with its view at the implied 0 + 90 = 90, Q:
//           H = 1 + 16/25 - 0.5 * 0 (dBeta = dAlpha = -90)          -> score 0.82.
//           Object 2 on L_0 with its only view S: H = 0 + 1 - 0.5 * pi/2 -> score (1 - pi/4)/2.
//   vci-w0: object 1 gets its most similar view R: (1 + 16/17) / 2; object 2: 1/2.
//   vci-bm: no extension: both (1 + 0) / 2 = 1/2.
// A device without an orientation sensor sends frames without azimuths: the engines then use
// the descriptors alone, each in its own way. VCI puts no orientation cost on a path and fills a
// list from the frame's most similar view: exactly vci-w0 on the same frames with azimuths. SIIS
// and EIIS take each frame's most similar view instead of the one the turn implies: exactly EIS.
// The HMM lets the object jump to any sector (a_ij = pi_j, equal for equal sectors), so each
// frame's path state is its best one: the score is the mean over frames of the best state's TC,
// the same whatever order the frames come in.
TEST(RecognitionEngineTest, WithoutAzimuthsTheEnginesUseTheDescriptorsAlone) {
  const auto index = CoilIndex(SearchMode::kExact);
  std::vector<QueryFrame> with = Frames(7, {95, 105, 115, 125, 135}, 40);
  // A frame of object 3, so that the rankings are not all the same object's.
  with[2].descriptor.values = CoilView(3, 15);
  std::vector<QueryFrame> without = with;
  for (QueryFrame& frame : without) frame.azimuth.reset();
  ExpectSameUpdate(CreateEngine("vci")->ObserveSequence(index, without),
                   CreateEngine("vci-w0")->ObserveSequence(index, with), "vci");
  const FrameUpdate eis = CreateEngine("eis")->ObserveSequence(index, with);
  for (const char* name : {"siis", "eiis"}) {
    const FrameUpdate update = CreateEngine(name)->ObserveSequence(index, without);
    ASSERT_EQ(update.ranking.size(), eis.ranking.size()) << name;
    for (std::size_t r = 0; r < update.ranking.size(); ++r) {
      EXPECT_EQ(update.ranking[r].object, eis.ranking[r].object) << name << " rank " << r;
      EXPECT_NEAR(update.ranking[r].score, eis.ranking[r].score, 1e-9) << name << " rank " << r;
    }
  }
  std::vector<QueryFrame> reversed(without.rbegin(), without.rend());
  const FrameUpdate hmm = CreateEngine("hmm", {.top_k = 10})->ObserveSequence(index, without);
  const FrameUpdate hmm_reversed =
      CreateEngine("hmm", {.top_k = 10})->ObserveSequence(index, reversed);
  ASSERT_EQ(hmm.ranking.size(), 10u);
  for (std::size_t r = 0; r < hmm.ranking.size(); ++r) {
    EXPECT_EQ(hmm.ranking[r].object, hmm_reversed.ranking[r].object) << "rank " << r;
    EXPECT_NEAR(hmm.ranking[r].score, hmm_reversed.ranking[r].score, 1e-6) << "rank " << r;
  }
  // The best score by hand: object 7's mean over frames of its best sector's TC.
  const IndexedObject& seven = *index->Find(7);
  const SectorViews& sectors = seven.Sectors(8);
  double sum = 0;
  for (const QueryFrame& frame : without) {
    double best = 0;
    for (const MeanDescriptor& mean : sectors.descriptor) {
      best = std::max(best, Tanimoto(frame.descriptor.values, mean));
    }
    sum += best;
  }
  ASSERT_EQ(hmm.ranking[0].object, 7);
  EXPECT_NEAR(hmm.ranking[0].score, sum / static_cast<double>(without.size()), 1e-6);
}

TEST(RecognitionEngineTest, ListExtensionByHand) {
  const DescriptorValues p = Bins({{0, 4}}), s = Bins({{1, 4}});
  const DescriptorValues q = Bins({{1, 4}, {3, 3}}), r = Bins({{1, 4}, {2, 1}});
  ViewIndex index(
      {{1, "one", DescriptorVariant::kCeddLire, {View(p, 0), View(q, 90), View(r, 180)}},
       {2, "two", DescriptorVariant::kCeddLire, {View(s, 0)}}});
  const std::vector<QueryFrame> frames = {{{DescriptorVariant::kCeddLire, p}, 200},
                                          {{DescriptorVariant::kCeddLire, s}, 290}};
  const auto scores = [&](std::string_view name) {
    const FrameUpdate u =
        CreateEngine(name, {.list_length = 1})->ObserveSequence(index.Snapshot(), frames);
    EXPECT_EQ(u.ranking.size(), 2u) << name;
    std::map<ObjectId, double> by_id;
    for (const RankedObject& ranked : u.ranking) by_id[ranked.object] = ranked.score;
    return by_id;
  };
  const auto vci = scores("vci");
  EXPECT_NEAR(vci.at(1), (1 + 16.0 / 25) / 2, 1e-12);
  EXPECT_NEAR(vci.at(2), (1 - std::numbers::pi / 4) / 2, 1e-12);
  const auto w0 = scores("vci-w0");
  EXPECT_NEAR(w0.at(1), (1 + 16.0 / 17) / 2, 1e-12);
  EXPECT_NEAR(w0.at(2), 0.5, 1e-12);
  const auto bm = scores("vci-bm");
  EXPECT_NEAR(bm.at(1), 0.5, 1e-12);
  EXPECT_NEAR(bm.at(2), 0.5, 1e-12);
}

// A session sees an object enrolled or deleted from its next frame on.
TEST(RecognitionEngineTest, SessionsSeeEnrolmentsAndDeletionsFromTheNextFrame) {
  std::vector<ObjectModel> models = CoilObjects(1, 10, EvenView);
  const ObjectModel four = models[3];
  models.erase(models.begin() + 3);
  for (const SearchMode mode : {SearchMode::kExact, SearchMode::kKdTree}) {
    ViewIndex index(models, {.search = mode});
    for (const std::string_view name : {"eis", "vci", "hmm"}) {
      const auto engine = CreateEngine(name);
      const std::vector<QueryFrame> frames = Frames(4, {25, 35, 45, 55}, 0);
      const FrameUpdate before = engine->Observe(index.Snapshot(), frames[0]);
      EXPECT_NE(before.ranking[0].object, 4);
      index.Add(four);
      engine->Observe(index.Snapshot(), frames[1]);
      const FrameUpdate after = engine->Observe(index.Snapshot(), frames[2]);
      EXPECT_EQ(after.ranking[0].object, 4) << name;
      ASSERT_TRUE(index.Remove(4));
      const FrameUpdate gone = engine->Observe(index.Snapshot(), frames[3]);
      for (const RankedObject& r : gone.ranking) EXPECT_NE(r.object, 4) << name;
      EXPECT_EQ(gone.frame_index, 3);
    }
  }
}

// An enrollment, an object gaining views, a deletion, and two changes at once, each while a
// session's window is full: the session's next answer is the one a fresh session given the same
// window on the new index gives (the engines bring only the changed objects' state up to date,
// so this checks that nothing stale survives and nothing is missed). Exact search, so that the
// VCI lists are exact too.
TEST(RecognitionEngineTest, AModelChangeGivesTheAnswerOfAFreshSessionOnTheNewIndex) {
  std::vector<ObjectModel> models = CoilObjects(1, 10, EvenView);
  const ObjectModel four = models[3];
  models.erase(models.begin() + 3);
  const ObjectModel three_complete = CoilObject(3);  // 72 views where the index has 36
  // Frames of object 3 (in the index, then replaced) and of object 4 (enrolled later).
  std::vector<QueryFrame> frames = Frames(3, {205, 215, 225, 235}, 11);
  for (const QueryFrame& frame : Frames(4, {25, 35, 45, 55, 65, 75}, -40)) frames.push_back(frame);
  constexpr int kWindow = 4;
  for (const std::string_view name : EngineNames()) {
    ViewIndex index(models, {.search = SearchMode::kExact});
    const auto session = CreateEngine(name, {.window = kWindow});
    // Before frame k, change the index as listed.
    const std::map<std::size_t, std::function<void()>> changes = {
        {4, [&] { index.Add(four); }},                // enrolled: the frames' object
        {5, [&] { index.Replace(three_complete); }},  // views added to a seen object
        {6, [&] { ASSERT_TRUE(index.Remove(2)); }},   // deleted
        {8,
         [&] {  // two changes between frames
           ASSERT_TRUE(index.Remove(4));
           index.Add(CoilObjects(11, 11, EvenView)[0]);
         }},
    };
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (const auto change = changes.find(k); change != changes.end()) change->second();
      const FrameUpdate update = session->Observe(index.Snapshot(), frames[k]);
      const std::size_t first = k + 1 > kWindow ? k + 1 - kWindow : 0;
      const auto fresh = CreateEngine(name, {.window = kWindow});
      FrameUpdate expected =
          fresh->ObserveSequence(index.Snapshot(), std::span(frames).subspan(first, k + 1 - first));
      expected.frame_index = static_cast<std::int64_t>(k);
      ExpectSameUpdate(update, expected, std::string(name) + " frame " + std::to_string(k));
    }
  }
}

TEST(RecognitionEngineTest, BadFramesAreRejectedAndLeaveTheSessionUnchanged) {
  const auto engine = CreateEngine("vci");
  const auto index = CoilIndex(SearchMode::kExact);
  QueryFrame wrong_variant{{DescriptorVariant::kCeddFull, CoilView(1, 5)}, 0};
  EXPECT_THROW(engine->Observe(index, wrong_variant), std::invalid_argument);
  QueryFrame not_finite{{DescriptorVariant::kCeddLire, CoilView(1, 5)}, NAN};
  EXPECT_THROW(engine->Observe(index, not_finite), std::invalid_argument);
  QueryFrame out_of_range{{DescriptorVariant::kCeddLire, CoilView(1, 5)}, 0};
  out_of_range.descriptor.values[17] = 8;
  EXPECT_THROW(engine->Observe(index, out_of_range), std::invalid_argument);
  for (const double sigma : {-0.5, 256.0, double(NAN)}) {
    QueryFrame bad_noise{{DescriptorVariant::kCeddLire, CoilView(1, 5)}, 0, sigma};
    EXPECT_THROW(engine->Observe(index, bad_noise), std::invalid_argument) << sigma;
  }
  for (const double blur : {-0.01, 1.01, double(NAN)}) {
    QueryFrame bad_blur{{DescriptorVariant::kCeddLire, CoilView(1, 5)}, 0, std::nullopt, blur};
    EXPECT_THROW(engine->Observe(index, bad_blur), std::invalid_argument) << blur;
  }
  EXPECT_THROW(engine->Observe(nullptr, Frames(1, {5}, 0)[0]), std::invalid_argument);
  EXPECT_THROW(engine->ObserveSequence(index, {}), std::invalid_argument);
  const FrameUpdate first = engine->Observe(index, Frames(1, {5}, 0)[0]);
  EXPECT_EQ(first.frame_index, 0);
  EXPECT_EQ(first.ranking[0].object, 1);
}

TEST(RecognitionEngineTest, EmptyIndexGivesAnEmptyUndecidedAnswer) {
  ViewIndex empty(DescriptorVariant::kCeddLire);
  for (const std::string_view name : EngineNames()) {
    const FrameUpdate u = CreateEngine(name)->Observe(empty.Snapshot(), Frames(1, {5}, 0)[0]);
    EXPECT_TRUE(u.ranking.empty()) << name;
    EXPECT_EQ(u.decision, Decision::kUndecided) << name;
    EXPECT_EQ(u.move, SuggestedMove::kNone) << name;
  }
}

// The baselines by hand. Object 1: views A (0), C (90), A (180), A (270); object 2: view B (45).
// Frame 0 = q (TC(q,A) = 0.8, TC(q,B) = 2/7, TC(q,C) = 0); frame 1 = C, turned by +200 degrees.
//   EIS:  object 1: (0.8 + 1) / 2 = 0.9 (each frame's best view, orientation ignored).
//   SIIS: frame 0's best view is A at 0; frame 1 is compared with the views around 200
//         (A at 180, A at 270): TC 0, so (0.8 + 0) / 2 = 0.4.
//   EIIS: anchoring frame 0 at A (180) puts frame 1 at 20, between A (0) and C (90): TC 1,
//         so (0.8 + 1) / 2 = 0.9.
//   Object 2 (one view) scores (2/7 + 0) / 2 = 1/7 in all three.
TEST(RecognitionEngineTest, BaselineScoresByHand) {
  const DescriptorValues q = Bins({{0, 2}}), a = Bins({{0, 2}, {1, 1}});
  const DescriptorValues b = Bins({{0, 1}, {2, 2}}), c = Bins({{5, 3}});
  const ObjectModel one{1,
                        "one",
                        DescriptorVariant::kCeddLire,
                        {View(a, 0), View(c, 90), View(a, 180), View(a, 270)}};
  const ObjectModel two{2, "two", DescriptorVariant::kCeddLire, {View(b, 45)}};
  ViewIndex index({one, two});
  const std::vector<QueryFrame> frames = {{{DescriptorVariant::kCeddLire, q}, 10},
                                          {{DescriptorVariant::kCeddLire, c}, 210}};
  const auto score = [&](std::string_view name, ObjectId id) {
    const FrameUpdate u = CreateEngine(name)->ObserveSequence(index.Snapshot(), frames);
    for (const RankedObject& r : u.ranking) {
      if (r.object == id) return r.score;
    }
    return -1.0;
  };
  EXPECT_NEAR(score("eis", 1), 0.9, 1e-7);
  EXPECT_NEAR(score("siis", 1), 0.4, 1e-7);
  EXPECT_NEAR(score("eiis", 1), 0.9, 1e-7);
  for (const std::string_view name : {"eis", "siis", "eiis"}) {
    EXPECT_NEAR(score(name, 2), 1.0 / 7, 1e-7) << name;
  }
}

// The nearest-view blend, by hand, on one frame q = (bin 0: 2, bin 1: 2), HMM with the thesis'
// emissions. Object 1 has views (bin 0: 4) at 0 and (bin 1: 4) at 10 degrees, one sector
// whose mean view is q itself: path TC 1, but each view alone only 8 / (8 + 16 - 8) = 0.5 (the
// two are taken at different elevations, so they are not blended: docs/design.md#blended-views).
// Object 2 has one view q + (bin 2: 1): TC 8 / (8 + 9 - 8) = 8/9 both ways. The HMM alone
// ranks 1 (1.0) over 2 (8/9); half from the nearest views, 2 (8/9) over 1 (0.75).
TEST(RecognitionEngineTest, NearestViewBlendByHand) {
  ObjectModel one{
      1, "one", DescriptorVariant::kCeddLire, {View(Bins({{0, 4}}), 0), View(Bins({{1, 4}}), 10)}};
  one.views[0].elevation = 0;
  one.views[1].elevation = 20;
  const ObjectModel two{
      2, "two", DescriptorVariant::kCeddLire, {View(Bins({{0, 2}, {1, 2}, {2, 1}}), 100)}};
  ViewIndex index({one, two});
  const std::vector<QueryFrame> frame = {
      {{DescriptorVariant::kCeddLire, Bins({{0, 2}, {1, 2}})}, 5}};
  const auto ranking = [&](double weight) {
    return CreateEngine("hmm", {.nearest_view_weight = weight})
        ->ObserveSequence(index.Snapshot(), frame)
        .ranking;
  };
  const std::vector<RankedObject> path = ranking(0), blend = ranking(0.5), nearest = ranking(1);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[0].object, 1);
  EXPECT_NEAR(path[0].score, 1.0, 1e-6);
  EXPECT_NEAR(path[1].score, 8.0 / 9, 1e-6);
  ASSERT_EQ(blend.size(), 2u);
  EXPECT_EQ(blend[0].object, 2);
  EXPECT_NEAR(blend[0].score, 8.0 / 9, 1e-6);
  EXPECT_EQ(blend[1].object, 1);
  EXPECT_NEAR(blend[1].score, 0.75, 1e-6);
  ASSERT_EQ(nearest.size(), 2u);
  EXPECT_EQ(nearest[0].object, 2);
  EXPECT_NEAR(nearest[1].score, 0.5, 1e-6);
}

// The same objects with object 1's two views at one elevation, 10 degrees apart: their mean is
// q, so the nearest-view term finds q between them (TC 1) and object 1 stays first at every
// weight, with 1.0 against object 2's 8/9.
TEST(RecognitionEngineTest, TheNearestViewTermFindsAFrameBetweenTwoNeighbouringViews) {
  const ObjectModel one{
      1, "one", DescriptorVariant::kCeddLire, {View(Bins({{0, 4}}), 0), View(Bins({{1, 4}}), 10)}};
  const ObjectModel two{
      2, "two", DescriptorVariant::kCeddLire, {View(Bins({{0, 2}, {1, 2}, {2, 1}}), 100)}};
  ViewIndex index({one, two});
  const std::vector<QueryFrame> frame = {
      {{DescriptorVariant::kCeddLire, Bins({{0, 2}, {1, 2}})}, 5}};
  for (const double weight : {0.5, 1.0}) {
    const std::vector<RankedObject> ranking = CreateEngine("hmm", {.nearest_view_weight = weight})
                                                  ->ObserveSequence(index.Snapshot(), frame)
                                                  .ranking;
    ASSERT_EQ(ranking.size(), 2u);
    EXPECT_EQ(ranking[0].object, 1) << weight;
    EXPECT_NEAR(ranking[0].score, 1.0, 1e-6) << weight;
    EXPECT_NEAR(ranking[1].score, 8.0 / 9, 1e-6) << weight;
  }
}

// On real frames, every ranked object's blended score is (1 - w) x the engine's own + w x the
// nearest-view term of the same window: per frame the best of the object's views (EIS' own
// similarity) and of its neighbouring views' blends, whatever the engine: the blend needs no
// engine's internals.
TEST(RecognitionEngineTest, NearestViewBlendIsTheEngineScoreMixedWithEis) {
  const std::vector<QueryFrame> frames = Frames(4, {95, 135, 175, 215}, 25);
  const std::shared_ptr<const ViewIndexSnapshot> index = CoilIndex(SearchMode::kExact);
  std::map<ObjectId, double> nearest;
  for (const ObjectSlot& slot : index->objects()) {
    double sum = 0;
    for (const QueryFrame& frame : frames) {
      float blended = 0;
      const std::vector<float> row = SimilarityRow(frame.descriptor.values, *slot.object, &blended);
      sum += std::max(*std::max_element(row.begin(), row.end()), blended);
    }
    nearest[slot.object->id()] = sum / static_cast<double>(frames.size());
  }
  for (const std::string_view name : {"hmm", "vci", "eiis"}) {
    std::map<ObjectId, double> own;
    for (const RankedObject& r :
         CreateEngine(name, {.top_k = 10})->ObserveSequence(index, frames).ranking) {
      own[r.object] = r.score;
    }
    const FrameUpdate blended = CreateEngine(name, {.top_k = 4, .nearest_view_weight = 0.3})
                                    ->ObserveSequence(index, frames);
    // (VCI ranks only the objects its retrieval lists hold.)
    ASSERT_EQ(blended.ranking.size(), std::min<std::size_t>(4, own.size())) << name;
    for (std::size_t i = 0; i < blended.ranking.size(); ++i) {
      const ObjectId object = blended.ranking[i].object;
      ASSERT_TRUE(own.contains(object) && nearest.contains(object)) << name << " object " << object;
      EXPECT_NEAR(blended.ranking[i].score, 0.7 * own[object] + 0.3 * nearest[object], 1e-6)
          << name << " object " << object;
      if (i > 0) {
        EXPECT_GE(blended.ranking[i - 1].score, blended.ranking[i].score) << name;
      }
    }
    EXPECT_EQ(blended.ranking[0].object, 4) << name;
  }
}

// The rejection rule end to end, with typical distances from the protocol's real distortions:
// the known objects' queries are accepted, and a query of an object the index does not hold is
// "unknown", for VCI and for the HMM.
//
// Th is 0.5 here, not the default 2 of docs/design.md#threshold-rule: the 15-pixel motion blur
// makes Ttyp large on 128x128 COIL views, so T_M / Ttyp is far below 0.5 for these known objects
// and above it for strangers: Th = 2 would accept every stranger (docs/results/engines-speed.md,
// "Rejection threshold on COIL-100 (observation)").
TEST(RecognitionEngineTest, UnknownObjectsAreRejectedKnownOnesAccepted) {
  std::vector<ObjectModel> models = CoilObjects(1, 6, EvenView);
  for (ObjectModel& model : models) {
    for (ModelView& view : model.views) {
      const std::string file =
          (testing::DataDir() / "coil-100" /
           (model.name + "__" + std::to_string(static_cast<int>(view.azimuth)) + ".png"))
              .string();
      view.typical_distance =
          DescribeView(ReadImageFile(file), DescriptorVariant::kCeddLire).typical_distance;
    }
  }
  ViewIndex index(models, {.search = SearchMode::kKdTree});
  for (const std::string_view name : {"vci", "hmm"}) {
    const auto engine = CreateEngine(name, {.threshold = 0.5});
    for (int object = 1; object <= 6; ++object) {
      const FrameUpdate known =
          engine->ObserveSequence(index.Snapshot(), Frames(object, {45, 55, 65, 75}, 0));
      EXPECT_EQ(known.ranking[0].object, object) << name;
      EXPECT_EQ(known.decision, Decision::kAccept) << name << " object " << object;
    }
    for (int stranger = 40; stranger <= 45; ++stranger) {
      const FrameUpdate unknown =
          engine->ObserveSequence(index.Snapshot(), Frames(stranger, {45, 55, 65, 75}, 0));
      EXPECT_EQ(unknown.decision, Decision::kUnknown) << name << " object " << stranger;
    }
  }
}

}  // namespace
}  // namespace orbit
