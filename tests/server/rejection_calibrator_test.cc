// RejectionCalibrator: follows the model set in the background, never holding a session back
// except for the very first calibration.
#include "server/rejection_calibrator.h"

#include <gtest/gtest.h>

#include "tests/support/coil_models.h"

namespace orbit::server {
namespace {

using testing::CoilObjects;
using testing::EvenView;

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
}

TEST(RejectionCalibratorTest, WaitsOnlyForTheFirstCalibration) {
  ViewIndex index(CoilObjects(1, 1, EvenView));
  RejectionCalibrator calibrator(index.Snapshot());
  EXPECT_FALSE(calibrator.For(index.Snapshot())->calibrated());  // one object: none possible
  index.Add(CoilObjects(2, 2, EvenView)[0]);
  // No calibration yet and now one is possible: this call waits for it.
  const auto first = calibrator.For(index.Snapshot());
  EXPECT_TRUE(first->calibrated());
  EXPECT_EQ(first->sampled_objects(), 2);
}

}  // namespace
}  // namespace orbit::server
