// AzimuthGaps on azimuths whose arcs are counted by hand.
#include "core/model/azimuth_gaps.h"

#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(AzimuthGapsTest, WiderThanAGivenWidthAcrossZero) {
  // 40, 83, 100, 100 and -10 (350): 40 -> 83 is 43 wide, 100 -> 350 is 250 and 350 -> 40 is 50;
  // 83 -> 100 is 17, and the two views at 100 leave nothing between them.
  const std::vector<AzimuthGap> gaps = AzimuthGaps({40, 83, 100, 100, -10}, 25);
  ASSERT_EQ(gaps.size(), 3u);
  EXPECT_EQ(gaps[0].from, 40);
  EXPECT_EQ(gaps[0].to, 83);
  EXPECT_EQ(gaps[1].from, 100);
  EXPECT_EQ(gaps[1].to, 350);
  EXPECT_EQ(gaps[2].from, 350);
  EXPECT_EQ(gaps[2].to, 40);
  EXPECT_EQ(gaps[2].width(), 50);
  EXPECT_TRUE(AzimuthGaps({40, 83}, 320).empty());  // 43 and 317 wide
  EXPECT_TRUE(AzimuthGaps({}, 25).empty());
  // Views all at one azimuth see one side: the circle is open.
  const std::vector<AzimuthGap> one_side = AzimuthGaps({10, 10, 370}, 25);
  ASSERT_EQ(one_side.size(), 1u);
  EXPECT_EQ(one_side[0].from, 10);
  EXPECT_EQ(one_side[0].width(), 360);
}

}  // namespace
}  // namespace orbit
