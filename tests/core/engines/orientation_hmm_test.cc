#include "core/engines/orientation_hmm.h"

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"
#include "core/engines/recognition_engine.h"
#include "core/index/indexed_object.h"
#include "core/index/view_index.h"
#include "tests/support/coil_models.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using Matrix = std::vector<std::vector<double>>;

TEST(OrientationHmmTest, EqualSectorsAndInitialProbabilities) {
  const std::vector<Arc> sectors = EqualSectors(8);
  ASSERT_EQ(sectors.size(), 8u);
  EXPECT_EQ(sectors[3].start, 135);
  EXPECT_EQ(sectors[3].width, 45);
  for (const double p : InitialProbabilities(sectors)) EXPECT_DOUBLE_EQ(p, 1.0 / 8);
  EXPECT_THROW(EqualSectors(0), std::invalid_argument);
}

// Four 90-degree sectors, Delta = +30: L_j = [90j - 30, 90j + 60) overlaps R_j over 60 degrees
// and R_{j-1} over 30, so a_jj = 2/3 and a_{j-1,j} = 1/3 (j - 1 taken circularly).
TEST(OrientationHmmTest, TransitionMatrixForEqualSectorsByHand) {
  const Matrix a = TransitionMatrix(EqualSectors(4), 30);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const double expected = i == j ? 2.0 / 3 : i == (j + 3) % 4 ? 1.0 / 3 : 0.0;
      EXPECT_NEAR(a[i][j], expected, 1e-12) << i << "," << j;
    }
  }
  // A turn the other way moves probability the other way; 390 is the same turn as 30.
  const Matrix back = TransitionMatrix(EqualSectors(4), -30);
  EXPECT_NEAR(back[1][0], 1.0 / 3, 1e-12);
  EXPECT_NEAR(back[3][0], 0.0, 1e-12);
  EXPECT_EQ(TransitionMatrix(EqualSectors(4), 390), a);
  // No turn: the identity. Half a turn: a permutation.
  EXPECT_EQ(TransitionMatrix(EqualSectors(4), 0)[2][2], 1.0);
  EXPECT_EQ(TransitionMatrix(EqualSectors(4), 180)[0][2], 1.0);
}

// Sectors [0,180), [180,270), [270,360); Delta = 90.
//   L_0 = [270, 90): half in R_0, half in R_2 -> a_00 = a_20 = 1/2.
//   L_1 = [90, 180): all in R_0 -> a_01 = 1.      L_2 = [180, 270): all in R_1 -> a_12 = 1.
// Columns sum to 1; rows do not (row 0 sums to 1.5) because the sectors differ in width.
TEST(OrientationHmmTest, TransitionMatrixForUnequalSectorsByHand) {
  const std::vector<Arc> sectors = {{0, 180}, {180, 90}, {270, 90}};
  const Matrix a = TransitionMatrix(sectors, 90);
  const Matrix expected = {{0.5, 1, 0}, {0, 0, 1}, {0.5, 0, 0}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a[i][j], expected[i][j], 1e-12) << i << "," << j;
  }
  const std::vector<double> pi = InitialProbabilities(sectors);
  EXPECT_DOUBLE_EQ(pi[0], 0.5);
  EXPECT_DOUBLE_EQ(pi[1], 0.25);
}

TEST(OrientationHmmTest, RowsAndColumnsSumToOneForEqualSectors) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> turn(-720, 720);
  for (const int states : {1, 3, 8, 12}) {
    for (int trial = 0; trial < 50; ++trial) {
      const Matrix a = TransitionMatrix(EqualSectors(states), turn(random));
      for (int i = 0; i < states; ++i) {
        double row = 0, column = 0;
        for (int j = 0; j < states; ++j) {
          row += a[i][j];
          column += a[j][i];
        }
        EXPECT_NEAR(row, 1, 1e-12);
        EXPECT_NEAR(column, 1, 1e-12);
      }
    }
  }
}

TEST(OrientationHmmTest, EmissionsNormaliseSimilarities) {
  EXPECT_EQ(Emissions(std::vector<double>{1, 3}), (std::vector<double>{0.25, 0.75}));
  EXPECT_EQ(Emissions(std::vector<double>{0, 0}), (std::vector<double>{0.5, 0.5}));
}

// The textbook example (Wikipedia, "Viterbi algorithm"): states Healthy, Fever; start 0.6/0.4;
// transitions H->H 0.7, H->F 0.3, F->H 0.4, F->F 0.6; observations normal, cold, dizzy with
// emissions H (0.5, 0.4, 0.1) and F (0.1, 0.3, 0.6). Best path H, H, F with probability
// 0.6*0.5 * 0.7*0.4 * 0.3*0.6 = 0.01512.
TEST(OrientationHmmTest, ViterbiOnATinyModel) {
  const std::vector<double> initial = {0.6, 0.4};
  const Matrix a = {{0.7, 0.3}, {0.4, 0.6}};
  const std::vector<Matrix> transitions = {a, a};
  const std::vector<std::vector<double>> emissions = {{0.5, 0.1}, {0.4, 0.3}, {0.1, 0.6}};
  const ViterbiPath path = Viterbi(initial, transitions, emissions);
  EXPECT_EQ(path.states, (std::vector<int>{0, 0, 1}));
  EXPECT_NEAR(std::exp(path.log_probability), 0.01512, 1e-12);
  // A forbidden transition forces the other path: with H->F impossible, F must start
  // (0.4*0.1 * 0.6*0.3 * 0.6*0.6 = 0.002592) or stay H (0.6*0.5*0.7*0.4*0.7*0.1 = 0.00588).
  const Matrix no_fever = {{1.0, 0.0}, {0.4, 0.6}};
  const ViterbiPath stuck = Viterbi(initial, std::vector<Matrix>{no_fever, no_fever}, emissions);
  EXPECT_EQ(stuck.states, (std::vector<int>{0, 0, 0}));
  EXPECT_NEAR(std::exp(stuck.log_probability), 0.6 * 0.5 * 1.0 * 0.4 * 1.0 * 0.1, 1e-12);
}

TEST(OrientationHmmTest, ViterbiRejectsMismatchedSizes) {
  const std::vector<double> initial = {0.5, 0.5};
  EXPECT_THROW(Viterbi(initial, std::vector<Matrix>{}, std::vector<std::vector<double>>{}),
               std::invalid_argument);
  using EmissionRows = std::vector<std::vector<double>>;
  EXPECT_THROW(Viterbi(initial, std::vector<Matrix>{}, EmissionRows{{0.5, 0.5}, {0.5, 0.5}}),
               std::invalid_argument);
  EXPECT_THROW(Viterbi(initial, std::vector<Matrix>{}, EmissionRows{{1.0}}), std::invalid_argument);
}

// The engine decodes all objects at once in SIMD lanes, with floats (BatchViterbi). Here it must
// agree, frame by frame as the window slides, with the textbook pipeline applied object by
// object: sector means, Emissions(), TransitionMatrix() of the measured change, log-space
// Viterbi(), then the mean TC along the path. Random objects with irregular azimuths (so some
// sectors are empty and use stand-ins) and random turns (across 0/360, large jumps, standstill).
// The engine against the reference Viterbi() in double precision, object by object, frame by
// frame; with hmm_sharpness s the reference's emissions are b^(2^s) and the score is still the
// mean TC along the decoded path.
void ExpectEngineAgreesWithReferenceViterbi(int sharpness) {
  std::mt19937 random(77);
  // CEDD-like: 20 of CEDD's 144 bins, so that random views overlap as real CEDDs do and the
  // reference's path is not decided by float rounding between near-equal tiny similarities.
  std::uniform_int_distribution<int> value(0, 7), bin(0, kCeddSize - 1);
  auto sparse_descriptor = [&] {
    DescriptorValues values{};
    for (int k = 0; k < 20; ++k) values[bin(random)] = static_cast<std::uint8_t>(value(random));
    return values;
  };
  std::vector<ObjectModel> models;
  for (int id = 1; id <= 24; ++id) {
    ObjectModel model;
    model.id = id;
    const int views = 3 + id % 7 * 5;
    std::uniform_real_distribution<double> azimuth(0, 360);
    for (int v = 0; v < views; ++v) {
      ModelView view;
      view.descriptor = sparse_descriptor();
      view.azimuth = azimuth(random);
      model.views.push_back(view);
    }
    models.push_back(model);
  }
  ViewIndex index(models, {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  const int states = 8;
  const int window = 6;
  EngineOptions options{.window = window, .hmm_states = states, .top_k = 24};
  options.hmm_sharpness = sharpness;
  auto engine = CreateEngine("hmm", options);

  const std::vector<Arc> sectors = EqualSectors(states);
  const std::vector<double> initial = InitialProbabilities(sectors);
  const std::vector<double> turns = {0, 31, 350, -12, 0, 95, -170, 7, 180, 44, -3, 200};
  std::vector<QueryFrame> frames;
  double azimuth = 300;
  for (std::size_t k = 0; k < turns.size(); ++k) {
    azimuth += turns[k];
    // Frames resemble object 5's views, with noise, so that rankings are not all near zero.
    DescriptorValues values = models[4].views[k % models[4].views.size()].descriptor;
    values[bin(random)] = static_cast<std::uint8_t>(value(random));
    frames.push_back({{DescriptorVariant::kCeddLire, values}, azimuth});
    const FrameUpdate update = engine->Observe(snapshot, frames.back());

    const std::size_t first = frames.size() > window ? frames.size() - window : 0;
    const std::span<const QueryFrame> kept(frames.begin() + first, frames.end());
    std::vector<Matrix> transitions;
    for (std::size_t t = 1; t < kept.size(); ++t) {
      transitions.push_back(
          TransitionMatrix(sectors, AzimuthChange(*kept[t - 1].azimuth, *kept[t].azimuth)));
    }
    std::map<ObjectId, double> expected;
    for (const ObjectModel& model : models) {
      const SectorViews means = ComputeSectorViews(model, states);
      std::vector<std::vector<double>> emissions, similarities;
      for (const QueryFrame& frame : kept) {
        std::vector<double> tc;
        for (int i = 0; i < states; ++i) {
          tc.push_back(Tanimoto(frame.descriptor.values, means.descriptor[i]));
        }
        std::vector<double> b = Emissions(tc);
        for (double& e : b) e = std::pow(e, 1 << sharpness);
        emissions.push_back(b);
        similarities.push_back(tc);
      }
      const ViterbiPath path = Viterbi(initial, transitions, emissions);
      double sum = 0;
      for (std::size_t t = 0; t < kept.size(); ++t) sum += similarities[t][path.states[t]];
      expected[model.id] = sum / static_cast<double>(kept.size());
    }
    ASSERT_EQ(update.ranking.size(), models.size()) << "frame " << k;
    for (std::size_t r = 0; r < update.ranking.size(); ++r) {
      EXPECT_NEAR(update.ranking[r].score, expected.at(update.ranking[r].object), 1e-6)
          << "sharpness " << sharpness << ", frame " << k << ", object "
          << update.ranking[r].object;
      if (r > 0) {
        EXPECT_GE(update.ranking[r - 1].score, update.ranking[r].score);
      }
    }
  }
}

TEST(OrientationHmmTest, EngineAgreesWithReferenceViterbiObjectByObject) {
  ExpectEngineAgreesWithReferenceViterbi(0);
}

TEST(OrientationHmmTest, SharpenedEngineAgreesWithReferenceViterbiObjectByObject) {
  ExpectEngineAgreesWithReferenceViterbi(4);
}

TEST(OrientationHmmTest, SharpnessOutsideItsRangeIsRefused) {
  EXPECT_EQ(testing::ErrorMessageOf([] {
              EngineOptions options;
              options.hmm_sharpness = kMaxHmmSharpness + 1;
              ValidateEngineOptions(options);
            }),
            "engine option hmm_sharpness must be in 0..5, got 6");
}

// An object none of whose views shares a bin with the frames has TC 0 with every state: its
// emissions are uniform (so its Viterbi path is arbitrary), but its score, the mean TC along the
// path, is 0, below an object that matches only a little.
TEST(OrientationHmmTest, AnObjectUnseenInEveryFrameScoresZero) {
  auto model = [](ObjectId id, int first_bin) {
    ObjectModel object;
    object.id = id;
    for (int v = 0; v < 8; ++v) {
      ModelView view;
      for (int b = first_bin; b < first_bin + 10; ++b) view.descriptor[b] = 3;
      view.azimuth = 45.0 * v;
      object.views.push_back(view);
    }
    return object;
  };
  // Object 1 uses bins 0..9; object 2 bins 100..109; the frames bins 5..14 (half of object 1's).
  ViewIndex index({model(1, 0), model(2, 100)}, {.search = SearchMode::kExact});
  auto engine = CreateEngine("hmm", {.window = 4, .top_k = 2});
  DescriptorValues frame{};
  for (int b = 5; b < 15; ++b) frame[b] = 3;
  FrameUpdate update;
  for (int k = 0; k < 4; ++k) {
    update = engine->Observe(index.Snapshot(), {{DescriptorVariant::kCeddLire, frame}, 20.0 * k});
  }
  ASSERT_EQ(update.ranking.size(), 2u);
  EXPECT_EQ(update.ranking[0].object, 1);
  // TC of half-overlapping blocks of equal values: 5 x 9 / (10 x 9 + 10 x 9 - 5 x 9) = 1/3.
  EXPECT_NEAR(update.ranking[0].score, 1.0 / 3, 1e-6);
  EXPECT_EQ(update.ranking[1].object, 2);
  EXPECT_EQ(update.ranking[1].score, 0.0);
}

// The engine decodes only the objects whose bound (the mean of their best emission per frame)
// can reach the ranking. Over all 100 COIL-100 objects, its top 5 must be exactly the first 5
// of a ranking that decodes every object (top_k = 100), scores to the last bit, and so must the
// decision, for frames of known objects and for frames that many objects match
// about equally (one colour bin: bounds close together, so more objects must be decoded).
TEST(OrientationHmmTest, DecodingOnlyObjectsThatCanRankGivesTheFullRankingsTop) {
  ViewIndex index(testing::CoilObjects(1, 100, testing::EvenView), {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  auto pruned = CreateEngine("hmm", {.top_k = 5});
  auto full = CreateEngine("hmm", {.top_k = 100});
  std::vector<QueryFrame> frames;
  for (const int object : {7, 42, 93}) {
    for (int azimuth = 5; azimuth < 120; azimuth += 10) {
      frames.push_back({{DescriptorVariant::kCeddLire, testing::CoilView(object, azimuth)},
                        static_cast<double>(azimuth)});
    }
  }
  for (int k = 0; k < 10; ++k) {
    DescriptorValues one_bin{};
    one_bin[k % 3] = static_cast<std::uint8_t>(1 + k % 7);
    frames.push_back({{DescriptorVariant::kCeddLire, one_bin}, 10.0 * k});
  }
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const FrameUpdate top = pruned->Observe(snapshot, frames[f]);
    const FrameUpdate all = full->Observe(snapshot, frames[f]);
    ASSERT_EQ(top.ranking.size(), 5u);
    ASSERT_EQ(all.ranking.size(), 100u);
    for (std::size_t r = 0; r < 5; ++r) {
      EXPECT_EQ(top.ranking[r].object, all.ranking[r].object) << "frame " << f << ", rank " << r;
      EXPECT_EQ(top.ranking[r].score, all.ranking[r].score) << "frame " << f << ", rank " << r;
    }
    EXPECT_EQ(top.decision, all.decision) << "frame " << f;
  }
}

// When many objects match each frame well but not along any path the measured turns allow,
// their bounds are high and their scores low: the engine must decode past them. 32 "jumpy"
// objects (ids 1-32) hold half of frame A's bins at 0 degrees and half of frame B's at 180,
// nothing elsewhere: TC 0.5 with every frame at some state (bound 0.5), but the device does not
// turn while the frames alternate A, B, so a path scores (0.5 + 0) / 2 = 0.25. 8 "steady" objects
// (ids 33-40) show M, half of A's bins and half of B's, all around: TC(A, M) = TC(B, M) =
// 45 / (90 + 90 - 45) = 1/3 in every frame, bound and score. The top 8 are the steady ones.
TEST(OrientationHmmTest, ObjectsWithHighBoundsButInconsistentPathsDoNotHideTheRightOnes) {
  auto bins = [](int first, int count) {
    DescriptorValues values{};
    for (int b = first; b < first + count; ++b) values[b] = 3;
    return values;
  };
  const DescriptorValues a = bins(0, 10), b = bins(10, 10);
  DescriptorValues m = bins(0, 5);
  for (int k = 10; k < 15; ++k) m[k] = 3;
  std::vector<ObjectModel> models;
  for (ObjectId id = 1; id <= 40; ++id) {
    ObjectModel model;
    model.id = id;
    for (int v = 0; v < 8; ++v) {
      ModelView view;
      view.azimuth = 45.0 * v;
      if (id > 32) {
        view.descriptor = m;
      } else {
        view.descriptor = v == 0 ? bins(0, 5) : v == 4 ? bins(10, 5) : bins(100, 10);
      }
      model.views.push_back(view);
    }
    models.push_back(model);
  }
  ViewIndex index(models, {.search = SearchMode::kExact});
  auto pruned = CreateEngine("hmm", {.window = 8, .top_k = 8});
  auto full = CreateEngine("hmm", {.window = 8, .top_k = 40});
  FrameUpdate top, all;
  for (int k = 0; k < 8; ++k) {
    const QueryFrame frame{{DescriptorVariant::kCeddLire, k % 2 == 0 ? a : b}, 90.0};
    top = pruned->Observe(index.Snapshot(), frame);
    all = full->Observe(index.Snapshot(), frame);
  }
  ASSERT_EQ(top.ranking.size(), 8u);
  for (std::size_t r = 0; r < 8; ++r) {
    EXPECT_EQ(top.ranking[r].object, static_cast<ObjectId>(33 + r)) << "rank " << r;
    EXPECT_NEAR(top.ranking[r].score, 1.0 / 3, 1e-6) << "rank " << r;
    EXPECT_EQ(top.ranking[r].object, all.ranking[r].object) << "rank " << r;
    EXPECT_EQ(top.ranking[r].score, all.ranking[r].score) << "rank " << r;
  }
  EXPECT_LT(all.ranking[8].score, 1.0 / 3);  // the best jumpy object
}

}  // namespace
}  // namespace orbit
