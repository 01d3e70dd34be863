// RejectionCalibrator: follows the model set in the background, never holding a session back
// except for the very first calibration, and only once the model set has changed enough.
#include "server/rejection_calibrator.h"

#include <sched.h>

#include <chrono>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/coil_models.h"

namespace orbit::server {
namespace {

using testing::CoilObjects;
using testing::EvenView;

ObjectModel Renumbered(ObjectModel model, ObjectId id) {
  model.id = id;
  model.name = "copy-" + std::to_string(id);
  return model;
}

TEST(RejectionCalibratorTest, RecalibratesInTheBackgroundAfterAChange) {
  ViewIndex index(CoilObjects(1, 4, EvenView));
  RejectionCalibrator calibrator(index.Snapshot());
  const auto before = calibrator.For(index.Snapshot());
  ASSERT_TRUE(before->calibrated());
  EXPECT_EQ(before->sampled_objects(), 4);

  index.Add(CoilObjects(5, 5, EvenView)[0]);
  const auto changed = index.Snapshot();
  // The session is answered at once with what there is, and the change is being calibrated.
  calibrator.For(changed);
  calibrator.TEST_WaitFor(*changed);
  const auto after = calibrator.For(changed);
  EXPECT_NE(after, before);
  EXPECT_EQ(after->sampled_objects(), 5);
  // The same snapshot again asks for nothing new.
  EXPECT_EQ(calibrator.For(changed), after);
  // With a calibration to keep serving, recalibrations run on the core's idle time only.
  EXPECT_EQ(calibrator.TEST_SchedulingPolicy(), SCHED_IDLE);
}

TEST(RejectionCalibratorTest, WaitsOnlyForTheFirstCalibration) {
  ViewIndex index(CoilObjects(1, 1, EvenView));
  RejectionCalibrator calibrator(index.Snapshot());
  EXPECT_FALSE(calibrator.For(index.Snapshot())->calibrated());  // one object: none possible
  // Sessions will wait for the first calibration, so it is not left to idle time, which a
  // saturated machine never has.
  EXPECT_EQ(calibrator.TEST_SchedulingPolicy(), SCHED_OTHER);
  index.Add(CoilObjects(2, 2, EvenView)[0]);
  // No calibration yet and now one is possible: this call waits for it.
  const auto first = calibrator.For(index.Snapshot());
  EXPECT_TRUE(first->calibrated());
  EXPECT_EQ(first->sampled_objects(), 2);
  // Once there is one, the thread gives the cores back to the sessions.
  EXPECT_EQ(calibrator.TEST_SchedulingPolicy(), SCHED_IDLE);
}

TEST(RejectionCalibratorTest, RecalibrationIsDueAfterOnePercentOfTheObjectsOrFiveMinutes) {
  EXPECT_FALSE(RecalibrationDue(0, 1000, 1e6, true));  // nothing changed
  EXPECT_TRUE(RecalibrationDue(1, 1000, 0, false));    // no calibration yet
  EXPECT_TRUE(RecalibrationDue(1, 100, 0, true));      // up to 100 objects: every change
  EXPECT_TRUE(RecalibrationDue(1, 2, 0, true));
  EXPECT_FALSE(RecalibrationDue(1, 150, 0, true));  // 1.5 needed
  EXPECT_TRUE(RecalibrationDue(2, 150, 0, true));
  EXPECT_FALSE(RecalibrationDue(9, 1000, 0, true));
  EXPECT_TRUE(RecalibrationDue(10, 1000, 0, true));
  EXPECT_FALSE(RecalibrationDue(1, 1000, 299, true));
  EXPECT_TRUE(RecalibrationDue(1, 1000, 300, true));
}

// 200 objects (COIL-100 twice over): one enrollment is half of the 1% a recalibration waits
// for, and the session keeps the calibration it has; a second one makes it due.
TEST(RejectionCalibratorTest, ASmallChangeWaitsForMore) {
  std::vector<ObjectModel> models = CoilObjects(1, 100, EvenView);
  for (int n = 0; n < 100; ++n) models.push_back(Renumbered(models[n], n + 101));
  ViewIndex index(std::move(models));
  RejectionCalibrator calibrator(index.Snapshot());
  const auto before = calibrator.For(index.Snapshot());
  ASSERT_EQ(before->sampled_objects(), 200);

  index.Add(Renumbered(CoilObjects(1, 1, EvenView)[0], 201));
  const auto one = index.Snapshot();
  EXPECT_EQ(calibrator.For(one), before);
  // Calibrating 200 objects takes far less than the 3 s waited here: it would have finished.
  EXPECT_FALSE(calibrator.TEST_WaitFor(*one, std::chrono::seconds(3)));
  EXPECT_EQ(calibrator.For(one), before);

  index.Add(Renumbered(CoilObjects(2, 2, EvenView)[0], 202));
  const auto two = index.Snapshot();
  calibrator.For(two);
  calibrator.TEST_WaitFor(*two);
  EXPECT_EQ(calibrator.For(two)->sampled_objects(), 202);
}

}  // namespace
}  // namespace orbit::server
