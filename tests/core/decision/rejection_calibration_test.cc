// RejectionCalibration on COIL-100: its thresholds mean what they say on objects it has never
// seen, and its arithmetic (quantiles, p-values, determinism, small model sets) is exact.
#include "core/decision/rejection_calibration.h"

#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"
#include "core/engines/recognition_engine.h"
#include "tests/support/coil_models.h"

namespace orbit {
namespace {

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
  const auto two = ViewIndex(CoilObjects(1, 2, EvenView)).Snapshot();
  EXPECT_TRUE(RejectionCalibration::FromIndex(*two).calibrated());
}

TEST(RejectionCalibrationTest, SamplesEveryViewOfASmallModelSet) {
  // 20 objects x 36 views = 720 views, under the 2048 sampled at most: all of them.
  EXPECT_EQ(KnownCalibration().sampled_objects(), 20);
  EXPECT_EQ(KnownCalibration().sampled_views(), 720);
}

TEST(RejectionCalibrationTest, ThresholdIsTheNullQuantileOfTheTargetRate) {
  const RejectionCalibration& calibration = KnownCalibration();
  for (const int n : {1, 4, 8}) {
    double previous = -1;
    for (const double rate : {0.01, 0.05, 0.15, 0.5}) {
      const double threshold = calibration.Threshold(n, rate);
      EXPECT_GT(threshold, previous) << "n " << n << ", rate " << rate;
      previous = threshold;
      // 2000 null values, some drawn more than once (a window of one frame is one of 720
      // views): the share at or below the threshold is the rate, never above it (the p-value
      // counts one value more), and below it by a few tied values at most.
      const double share = calibration.FalseAcceptRate(threshold, n);
      EXPECT_LE(share, rate + 1.0 / 2000 + 1e-9) << "n " << n << ", rate " << rate;
      EXPECT_GE(share, rate - 8.0 / 2000) << "n " << n << ", rate " << rate;
    }
  }
  // Windows longer than the calibrated ones use the longest one's null.
  EXPECT_EQ(calibration.Threshold(64, 0.15), calibration.Threshold(kCalibratedWindowLengths, 0.15));
}

TEST(RejectionCalibrationTest, IsTheSameForTheSameSeed) {
  const RejectionCalibration again = RejectionCalibration::FromIndex(*KnownIndex());
  EXPECT_EQ(again.Threshold(8, 0.15), KnownCalibration().Threshold(8, 0.15));
  const RejectionCalibration other = RejectionCalibration::FromIndex(
      *KnownIndex(), {.max_sampled_views = 2048, .windows_per_length = 2000, .seed = 2});
  EXPECT_NE(other.Threshold(8, 0.15), KnownCalibration().Threshold(8, 0.15));
}

// 4-frame sweeps (views 15, 35, 55, 75 degrees on, never enrolled) of every known object and of
// ten objects the index does not hold, decided by the HMM with the calibrated rule.
struct Decisions {
  int known_accepted = 0;
  int unknown_accepted = 0;
};

Decisions DecideSweeps(double false_accept_rate) {
  EngineOptions options;
  options.rejection = RejectionRule::kCalibrated;
  options.false_accept_rate = false_accept_rate;
  auto engine = CreateEngine("hmm", options);
  engine->SetCalibration(std::make_shared<const RejectionCalibration>(KnownCalibration()));
  Decisions decisions;
  for (int object = 1; object <= 30; ++object) {
    for (const int start : {15, 195}) {
      std::vector<QueryFrame> frames;
      for (int k = 0; k < 4; ++k) {
        const int azimuth = start + 20 * k;
        frames.push_back({{DescriptorVariant::kCeddLire, CoilView(object, azimuth)},
                          static_cast<double>(azimuth)});
      }
      const FrameUpdate update = engine->ObserveSequence(KnownIndex(), frames);
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

}  // namespace
}  // namespace orbit
