// RejectionCalibration on COIL-100: its thresholds mean what they say on objects it has never
// seen, and its arithmetic (quantiles, p-values, determinism, small model sets) is exact.
#include "core/decision/rejection_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"
#include "core/engines/product_pipeline.h"
#include "core/engines/recognition_engine.h"
#include "evaluation/dataset.h"
#include "evaluation/evaluation_runner.h"
#include "tests/support/coil_models.h"
#include "tests/support/eth_images.h"
#include "tests/support/hand_made_descriptors.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilObject;
using testing::CoilObjects;
using testing::CoilView;
using testing::EvenView;

// Objects 1..20 with their views at multiples of 10 degrees.
std::shared_ptr<const ViewIndexSnapshot> KnownIndex() {
  static const auto index = ViewIndex(CoilObjects(1, 20, EvenView)).Snapshot();
  return index;
}

const RejectionCalibration& KnownCalibration() {
  static const RejectionCalibration calibration = RejectionCalibration::FromIndex(*KnownIndex());
  return calibration;
}

TEST(RejectionCalibrationTest, NeedsTwoObjects) {
  const auto one = ViewIndex(CoilObjects(1, 1, EvenView)).Snapshot();
  EXPECT_FALSE(RejectionCalibration::FromIndex(*one).calibrated());
  EXPECT_FALSE(RejectionCalibration().calibrated());
  constexpr int kFirst = 5;  // objects 5 and 6
  const auto two = ViewIndex(CoilObjects(kFirst, kFirst + 1, EvenView)).Snapshot();
  EXPECT_TRUE(RejectionCalibration::FromIndex(*two).calibrated());
}

TEST(RejectionCalibrationTest, SamplesEveryViewOfASmallModelSet) {
  // 20 objects x 36 views = 720 views, under the 2048 sampled at most: all of them.
  EXPECT_EQ(KnownCalibration().sampled_objects(), 20);
  EXPECT_EQ(KnownCalibration().sampled_views(), 720);
}

TEST(RejectionCalibrationTest, ThresholdIsTheLargestNullValueWhoseBoundMeetsTheTarget) {
  const RejectionCalibration& calibration = KnownCalibration();
  for (const int n : {1, 4, 8}) {
    double previous = -1;
    for (const double rate : {0.01, 0.05, 0.15, 0.5}) {
      const double threshold = calibration.NullThreshold(n, rate);
      EXPECT_GT(threshold, previous) << "n " << n << ", rate " << rate;
      previous = threshold;
      // The p-value at the threshold meets the target, the next null value's does not.
      EXPECT_LE(calibration.FalseAcceptRate(threshold, n), rate) << "n " << n << ", rate " << rate;
      double next = threshold + 1e-6;
      while (calibration.NullShare(next, n) == calibration.NullShare(threshold, n)) next += 1e-3;
      EXPECT_GT(calibration.FalseAcceptRate(next, n), rate) << "n " << n << ", rate " << rate;
      // The bound lies above the share the null's windows show: the threshold accepts less
      // of the null than the target, and no more than the bound's margin less. Shares in
      // [0, 1] over 20 objects have a standard deviation of at most 0.5 * sqrt(20 / 19), so
      // a standard error of at most 0.115 (and one tied window's worth on top).
      const double share = calibration.NullShare(threshold, n);
      EXPECT_LT(share, rate) << "n " << n << ", rate " << rate;
      EXPECT_GT(share, rate - kNullShareBoundSigmas * 0.115 - 0.005)
          << "n " << n << ", rate " << rate;
    }
  }
  // Windows longer than the calibrated ones use the longest one's null.
  EXPECT_EQ(calibration.NullThreshold(64, 0.15),
            calibration.NullThreshold(kCalibratedWindowLengths, 0.15));
}

TEST(RejectionCalibrationTest, TheKnownShareRaisesTheThresholdWithinItsBounds) {
  const RejectionCalibration& calibration = KnownCalibration();
  int raised = 0;  // the cases where the known windows set the threshold
  for (const int n : {1, 4, 8}) {
    const double most = calibration.NullThreshold(n, kMostFalseAcceptRate);
    for (const double rate : {0.02, 0.08, 0.5}) {
      const double least = calibration.NullThreshold(n, rate);
      // Without the known share: the null's threshold alone.
      EXPECT_EQ(calibration.Threshold(n, rate, 0), least) << "n " << n << ", rate " << rate;
      for (const double share : {0.5, 0.95, 0.999}) {
        const double threshold = calibration.Threshold(n, rate, share);
        const std::string where = "n " + std::to_string(n) + ", rate " + std::to_string(rate) +
                                  ", share " + std::to_string(share);
        // Never below the target's threshold, never raised above the most's.
        EXPECT_GE(threshold, least) << where;
        EXPECT_LE(threshold, std::max(least, most)) << where;
        if (threshold > least && threshold < most) {
          // Raised exactly to where the share of the known windows is accepted.
          ++raised;
          EXPECT_GE(calibration.KnownAcceptRate(threshold, n), share) << where;
          EXPECT_LE(calibration.KnownAcceptRate(std::nextafter(threshold, 0.0), n), share) << where;
        } else if (threshold == least && least < most) {
          // Not raised: the target's threshold accepted the share already.
          EXPECT_GE(calibration.KnownAcceptRate(threshold, n), share) << where;
        }
      }
    }
  }
  EXPECT_GT(raised, 0);
}

// Nine of eth-80-dev's toy cars enrolled (objects 11-19), each view cut to its box grown by 10% a
// side, and car9 (object 20) left out. A left-out car looks about as known as an enrolled car's
// own windows, so the null's threshold at the product's target rejects known cars too (21 of
// 27 queries right and accepted at n = 4); the known share raises it to accept more of them (25
// of 27), and the unknown car is still rejected.
TEST(RejectionCalibrationTest, TheKnownShareAcceptsLookAlikeCarsAndStillRejectsAnUnknownOne) {
  const SelectedImages images = testing::CroppedEthRing("11-19", "20");
  const auto run = [&images](double known_accept_rate) {
    EvaluationOptions options;
    options.methods = {std::string(kProductMethod)};
    options.distortions = {ParseDistortionSpec("df")};
    options.query_lengths = {4};
    options.trials = 3;
    options.seed = 5;
    options.engine.known_accept_rate = known_accept_rate;
    const EvaluationReport report = RunEvaluation(images.known, images.unknown, options);
    EXPECT_EQ(report.cells.size(), 1u);
    return report.cells.at(0);
  };
  const EvaluationCell null_alone = run(0);
  const EvaluationCell product = run(Product().options.known_accept_rate);
  ASSERT_EQ(product.trials, 27);
  ASSERT_EQ(product.unknown_trials, 3);
  EXPECT_LE(null_alone.accepted, 22) << "of 27";
  EXPECT_GE(product.accepted, 24) << "of 27";
  EXPECT_EQ(null_alone.rejected, 3) << "of 3";
  EXPECT_EQ(product.rejected, 3) << "of 3";
}

TEST(RejectionCalibrationTest, FewObjectsBoundTheShareFurtherBelowTheTarget) {
  // The same target on 5 of the 20 objects: the bound over five objects' shares lies further
  // above their mean, and the threshold accepts a smaller share of the null.
  const auto five = ViewIndex(CoilObjects(1, 5, EvenView)).Snapshot();
  const RejectionCalibration few = RejectionCalibration::FromIndex(*five);
  for (const int n : {1, 4}) {
    const double few_share = few.NullShare(few.NullThreshold(n, 0.17), n);
    const double many_share =
        KnownCalibration().NullShare(KnownCalibration().NullThreshold(n, 0.17), n);
    EXPECT_LT(few_share, many_share) << "n " << n;
    EXPECT_LE(few.FalseAcceptRate(few.NullThreshold(n, 0.17), n), 0.17) << "n " << n;
  }
}

TEST(RejectionCalibrationTest, PValueIsTheBoundAndNeverZero) {
  const RejectionCalibration& calibration = KnownCalibration();
  for (const int n : {1, 4}) {
    // Below every null value: one window's worth; above every one: the whole null.
    EXPECT_DOUBLE_EQ(calibration.FalseAcceptRate(-1, n), 1.0 / 2001);
    EXPECT_EQ(calibration.NullShare(-1, n), 0);
    EXPECT_GE(calibration.FalseAcceptRate(1e9, n), 1 - 1e-9);
    EXPECT_EQ(calibration.NullShare(1e9, n), 1);
    for (const double u : {0.5, 1.0, 1.5}) {
      EXPECT_GE(calibration.FalseAcceptRate(u, n), calibration.NullShare(u, n)) << u;
    }
  }
}

TEST(RejectionCalibrationTest, IsTheSameForTheSameSeed) {
  const RejectionCalibration again = RejectionCalibration::FromIndex(*KnownIndex());
  EXPECT_EQ(again.NullThreshold(8, 0.15), KnownCalibration().NullThreshold(8, 0.15));
  const RejectionCalibration other = RejectionCalibration::FromIndex(
      *KnownIndex(), {.max_sampled_views = 2048, .windows_per_length = 2000, .seed = 2});
  EXPECT_NE(other.NullThreshold(8, 0.15), KnownCalibration().NullThreshold(8, 0.15));
}

// A catalogue of 1,001 look-alike objects, above kScanEveryObjectUpTo: object k (0..1000) holds
// COIL-100 object k % 100 + 1's views at 5 * (k / 100) + 0, 90, 180 and 270 degrees, so each
// COIL-100 object stands for 10 or 11 objects whose views lie 5 to 50 degrees apart.
std::shared_ptr<const ViewIndexSnapshot> LargeIndex() {
  static const auto index =
      ViewIndex(testing::CoilLookAlikes(static_cast<int>(kScanEveryObjectUpTo) + 1)).Snapshot();
  return index;
}

const RejectionCalibration& LargeCalibration() {
  static const RejectionCalibration calibration = RejectionCalibration::FromIndex(*LargeIndex());
  return calibration;
}

// Above kScanEveryObjectUpTo objects a left-out object's views are scored against the objects its
// views propose, not against every object; among look-alikes the winner and the runner-up of its
// windows are among them, so the rule's thresholds are the ones a scan of every object gives.
TEST(RejectionCalibrationTest, ALargeCatalogueCalibratesFromCandidatesAsFromEveryObject) {
  const RejectionCalibration& candidates = LargeCalibration();
  const RejectionCalibration every = RejectionCalibration::FromIndex(
      *LargeIndex(), {.scan_every_object_up_to = LargeIndex()->object_count()});
  // 2048 / 1001 objects: two views of each.
  EXPECT_EQ(candidates.sampled_objects(), 1001);
  EXPECT_EQ(candidates.sampled_views(), 2002);
  for (const int n : {1, 4, 16}) {
    EXPECT_NEAR(candidates.NullThreshold(n, 0.17), every.NullThreshold(n, 0.17), 1e-6) << n;
    EXPECT_NEAR(candidates.NullThreshold(n, 0.05), every.NullThreshold(n, 0.05), 1e-6) << n;
    EXPECT_NEAR(candidates.KnownCeiling(n), every.KnownCeiling(n), 1e-6) << n;
    // Look-alikes 5 degrees apart: an unknown window looks nearly as known as a known one.
    EXPECT_LT(candidates.NullThreshold(n, 0.17), 1) << n;
  }
}

TEST(RejectionCalibrationTest, ThreadsChangeNothingAndManyObjectsSampleOneViewOfSome) {
  const RejectionCalibration& one = LargeCalibration();
  const RejectionCalibration two = RejectionCalibration::FromIndex(*LargeIndex(), {.threads = 2});
  for (const int n : {1, 8}) {
    EXPECT_EQ(one.NullThreshold(n, 0.17), two.NullThreshold(n, 0.17)) << n;
    EXPECT_EQ(one.KnownCeiling(n), two.KnownCeiling(n)) << n;
  }
  // More objects than sampled views: one view of each of 500 objects spread over the index.
  const RejectionCalibration some =
      RejectionCalibration::FromIndex(*LargeIndex(), {.max_sampled_views = 500});
  EXPECT_EQ(some.sampled_objects(), 500);
  EXPECT_EQ(some.sampled_views(), 500);
  EXPECT_TRUE(some.calibrated());
  EXPECT_THROW(RejectionCalibration::FromIndex(*LargeIndex(), {.threads = 0}),
               std::invalid_argument);
}

// 4-frame sweeps (views 15, 35, 55, 75 degrees on, never enrolled) of every known object and of
// ten objects the index does not hold, decided by the HMM with the calibrated rule.
struct Decisions {
  int known_accepted = 0;
  int unknown_accepted = 0;
};

// Views start, start + 20, start + 40, start + 60 of `object`, with their azimuths.
std::vector<QueryFrame> Sweep(int object, int start) {
  std::vector<QueryFrame> frames;
  for (int k = 0; k < 4; ++k) {
    const int azimuth = start + 20 * k;
    frames.push_back(
        {{DescriptorVariant::kCeddLire, CoilView(object, azimuth)}, static_cast<double>(azimuth)});
  }
  return frames;
}

Decisions DecideSweeps(double false_accept_rate) {
  EngineOptions options;
  options.rejection = RejectionRule::kCalibrated;
  options.false_accept_rate = false_accept_rate;
  auto engine = CreateEngine("hmm", options);
  engine->SetCalibration(std::make_shared<const RejectionCalibration>(KnownCalibration()));
  Decisions decisions;
  for (int object = 1; object <= 30; ++object) {
    for (const int start : {15, 195}) {
      const FrameUpdate update = engine->ObserveSequence(KnownIndex(), Sweep(object, start));
      if (update.decision != Decision::kAccept) continue;
      if (object <= 20) {
        decisions.known_accepted += update.ranking[0].object == object;
      } else {
        ++decisions.unknown_accepted;
      }
    }
  }
  return decisions;
}

TEST(RejectionCalibrationTest, AcceptsKnownObjectsAndRejectsUnseenOnes) {
  // 40 known sweeps, 20 unknown ones.
  const Decisions product = DecideSweeps(0.15);
  EXPECT_GE(product.known_accepted, 38) << "of 40";
  EXPECT_LE(product.unknown_accepted, 6) << "of 20";
  // A stricter target accepts fewer unknown objects.
  const Decisions strict = DecideSweeps(0.02);
  EXPECT_GE(strict.known_accepted, 36) << "of 40";
  EXPECT_LE(strict.unknown_accepted, 2) << "of 20";
  EXPECT_LE(strict.unknown_accepted, product.unknown_accepted);
}

// Two enrolled objects (COIL-100 5 and 6, unlike each other): their one pair is the whole null, and
// the null's quantile lies far above what either object's own windows need; the known ceiling holds
// the threshold there.
TEST(RejectionCalibrationTest, TwoObjectsHoldTheThresholdAtWhatTheirOwnViewsNeed) {
  constexpr int kFirst = 5;  // objects 5 and 6
  const auto two = ViewIndex(CoilObjects(kFirst, kFirst + 1, EvenView)).Snapshot();
  const RejectionCalibration calibration = RejectionCalibration::FromIndex(*two);
  for (const int n : {1, 4, 16}) {
    const double ceiling = calibration.KnownCeiling(n);
    EXPECT_LT(ceiling, calibration.NullThreshold(n, 0.17)) << "n " << n;
    // The margin above the known windows' quantile.
    const double quantile = ceiling / kKnownCeilingMargin;
    EXPECT_GE(calibration.KnownAcceptRate(quantile, n), kKnownWindowsAccepted) << "n " << n;
    EXPECT_LE(calibration.KnownAcceptRate(quantile - 1e-9, n), kKnownWindowsAccepted) << "n " << n;
  }
  // 4-frame sweeps of the two objects and of 20 objects the index does not hold.
  EngineOptions options;
  options.rejection = RejectionRule::kCalibrated;
  options.false_accept_rate = 0.17;
  auto engine = CreateEngine("hmm", options);
  engine->SetCalibration(std::make_shared<const RejectionCalibration>(calibration));
  int known_accepted = 0, unknown_accepted = 0, unknown_under_null = 0;
  for (int object = 1; object <= 40; ++object) {
    if (object < kFirst || (object > kFirst + 1 && object < 21)) continue;
    for (const int start : {15, 195}) {
      const FrameUpdate update = engine->ObserveSequence(two, Sweep(object, start));
      const bool accepted = update.decision == Decision::kAccept;
      if (object <= kFirst + 1) {
        known_accepted += accepted && update.ranking[0].object == object;
      } else {
        unknown_accepted += accepted;
        unknown_under_null += update.unknown_statistic <= calibration.NullThreshold(4, 0.17);
      }
    }
  }
  // 4 known sweeps, 40 unknown ones: the null's quantile alone would accept more than the
  // target's share of the unknown ones (17% of 40: 6.8), the ceiling keeps within it.
  EXPECT_EQ(known_accepted, 4);
  EXPECT_GT(unknown_under_null, 6) << "of 40";
  EXPECT_LE(unknown_accepted, 6) << "of 40";
}

// An object of three views at 0, 20 and 40 degrees, one of them (`mean_at`) the mean of the
// other two, and a second object far from it (views at 0 and 180, nothing in common).
RejectionCalibration BlendCalibration(int mean_at) {
  const DescriptorValues a = testing::Bins({{0, 4}, {1, 2}});
  const DescriptorValues b = testing::Bins({{0, 4}, {2, 2}});
  const DescriptorValues mean = testing::Bins({{0, 4}, {1, 1}, {2, 1}});
  std::vector<ObjectModel> models(2);
  models[0].id = 1;
  models[0].name = "blend";
  const std::vector<DescriptorValues> descriptors = mean_at == 0
                                                        ? std::vector<DescriptorValues>{mean, a, b}
                                                        : std::vector<DescriptorValues>{a, mean, b};
  for (int v = 0; v < 3; ++v)
    models[0].views.push_back({descriptors[v], 20.0 * v, std::nullopt, 0.1});
  models[1].id = 2;
  models[1].name = "far";
  models[1].views = {{testing::Bins({{3, 4}}), 0, std::nullopt, 0.1},
                     {testing::Bins({{4, 4}}), 180, std::nullopt, 0.1}};
  return RejectionCalibration::FromIndex(*ViewIndex(std::move(models)).Snapshot());
}

TEST(RejectionCalibrationTest, AKnownWindowReadsTheBlendsOfItsObjectsPairsOutsideItsNeighbourhood) {
  // The mean at 0: its neighbourhood (10 degrees) leaves the views at 20 and 40, a pair of the
  // object whose blend is the frame itself: d1 = 0, U = 0.
  EXPECT_GT(BlendCalibration(0).KnownAcceptRate(0, 1), 0);
  // The mean at 20: the views either side of its neighbourhood are no pair of the object (each
  // of its pairs holds the view at 20), so its best is a view at TC 18/20 = 0.9 and U =
  // 0.1 / 1 + 0.2 * 0.1 / 0.1 = 0.3 (the far object the runner-up at TC 0); so is every other
  // known window's (the blend of the mean and an outer view reaches 68/86 from the other).
  const RejectionCalibration between = BlendCalibration(20);
  EXPECT_EQ(between.KnownAcceptRate(0.3 - 1e-6, 1), 0);
  EXPECT_GT(between.KnownAcceptRate(0.3 + 1e-6, 1), 0);
}

TEST(RejectionCalibrationTest, AnObjectOfOneViewHasNoKnownWindows) {
  // Each object a single view: none has a view outside its own neighbourhood.
  const auto single =
      ViewIndex(CoilObjects(1, 3, [](int azimuth) { return azimuth == 0; })).Snapshot();
  const RejectionCalibration calibration = RejectionCalibration::FromIndex(*single);
  ASSERT_TRUE(calibration.calibrated());
  EXPECT_EQ(calibration.KnownCeiling(4), std::numeric_limits<double>::infinity());
  EXPECT_EQ(calibration.KnownAcceptRate(0, 4), 1);
}

}  // namespace
}  // namespace orbit
