// The object's region (client/object_region.h): the box grown by the margin and clipped to the
// image, and the messages for a box that does not lie inside the image.
#include "client/object_region.h"

#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ErrorMessageOf;

TEST(ObjectRegionTest, GrowsTheBoxByTheMarginOnEverySideThenClipsItToTheImage) {
  // eth-80-dev's apple1-090-000.jpg (256x256), boxed 32,32,192,191: round(19.2) = 19 and
  // round(19.1) = 19 a side, inside the image.
  EXPECT_EQ(ObjectRegion({32, 32, 192, 191}, 0.1, {256, 256}, "box"), cv::Rect(13, 13, 230, 229));
  // At the top-left corner, a quarter a side: 25 and round(12.5) = 13, clipped at 0 on the left
  // and top, not on the right and bottom.
  EXPECT_EQ(ObjectRegion({0, 0, 100, 50}, 0.25, {640, 480}, "box"), cv::Rect(0, 0, 125, 63));
  // A box filling the image: the margin has nowhere to go.
  EXPECT_EQ(ObjectRegion({0, 0, 640, 480}, 1.0, {640, 480}, "box"), cv::Rect(0, 0, 640, 480));
  // No margin: the box itself.
  EXPECT_EQ(ObjectRegion({10, 20, 30, 40}, 0, {640, 480}, "box"), cv::Rect(10, 20, 30, 40));
  EXPECT_EQ(kDefaultBoxMargin, 0.1);
}

TEST(ObjectRegionTest, ABoxNotInsideTheImageIsRefusedNamingItsOriginAndTheRange) {
  const cv::Size image(640, 480);
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({10, 10, 900, 20}, 0.1, image, "--box 10,10,900,20");
            }),
            "--box 10,10,900,20: x+w must be at most the image's width 640");
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({10, 470, 20, 11}, 0.1, image, "boxes.csv:3");
            }),
            "boxes.csv:3: y+h must be at most the image's height 480");
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({640, 0, 1, 1}, 0.1, image, "b");
            }),
            "b: x+w must be at most the image's width 640");
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({-1, 0, 10, 10}, 0.1, image, "b");
            }),
            "b: x and y must be at least 0");
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({0, 0, 0, 10}, 0.1, image, "b");
            }),
            "b: w and h must be at least 1");
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({0, 0, 10, 10}, 1.5, image, "b");
            }),
            "box margin must be in 0..1, got 1.500000");
  EXPECT_EQ(ErrorMessageOf([&] { CheckBoxMargin(-0.1); }),
            "box margin must be in 0..1, got -0.100000");
  // Coordinates whose sum overflows an int are refused, not wrapped round.
  EXPECT_EQ(ErrorMessageOf([&] {
              ObjectRegion({2'000'000'000, 0, 2'000'000'000, 1}, 0, image, "b");
            }),
            "b: x+w must be at most the image's width 640");
}

}  // namespace
}  // namespace orbit
