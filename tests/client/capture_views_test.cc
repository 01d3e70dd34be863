// Choosing enrollment views from a walk (client/capture_views.h): one view per azimuth step, the
// sharpest usable frame of the step, never a blurred, noisy or lost frame.
#include "client/capture_views.h"

#include <set>

#include <gtest/gtest.h>

#include "evaluation/capture_generator.h"
#include "tests/support/capture_walks.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ScratchDir;

TEST(CaptureViewsTest, KeepsTheSharpestUsableFrameOfEachStep) {
  const ScratchDir dir;
  // 3 degrees of walk per frame: two or three frames per 10-degree step.
  const testing::WrittenWalk walk = testing::WriteWalk(dir, testing::CoilWalk(9, 60, 180));

  CaptureReader reader(walk.video, OrientationLog::ReadFile(walk.log),
                       {.first_box = walk.capture.true_boxes[0]});
  long progress_calls = 0;
  const CaptureViewSelection selection =
      SelectCaptureViews(reader, {.step_deg = 10, .progress = [&](long read, long total) {
                                    EXPECT_EQ(total, 60);
                                    progress_calls = read;
                                  }});
  EXPECT_EQ(progress_calls, 60);
  EXPECT_EQ(selection.frames_read, 60);
  EXPECT_EQ(selection.frames_lost, 0);
  EXPECT_EQ(selection.steps_total, 36);
  // The log turns 180 degrees plus drift and noise: about 18 or 19 steps of 10 degrees.
  EXPECT_GE(selection.views.size(), 17u);
  EXPECT_LE(selection.views.size(), 20u);
  std::set<int> steps;
  long previous = -1;
  for (const CaptureView& view : selection.views) {
    EXPECT_GT(view.frame_index, previous);  // in frame order
    previous = view.frame_index;
    EXPECT_FALSE(walk.capture.degraded[view.frame_index]) << "frame " << view.frame_index;
    EXPECT_TRUE(steps.insert(static_cast<int>(view.image.azimuth_deg / 10)).second);
    EXPECT_EQ(view.image.image.size(), view.region.size());
    EXPECT_FALSE(view.image.region.has_value());
  }
  // Every degraded frame that was not outdone by a sharper one in its step counts as unusable.
  EXPECT_GE(selection.frames_unusable, 1);
}

}  // namespace
}  // namespace orbit
