// The device-side description of views for enrollment (client/enroller.h, ComputeView): what
// the server will store for an image or a region of it.
#include "client/enroller.h"

#include <gtest/gtest.h>

#include "core/cedd.h"
#include "core/view_description.h"
#include "tests/support/client_test_support.h"

namespace orbit {
namespace {

using testing::CoilImage;

TEST(EnrollerTest, ComputeViewIsTheCeddAndTypicalDistanceOfTheImageOrRegion) {
  const cv::Mat image = CoilImage(7, 40);
  const v1::View view =
      ComputeView({image, 40.0, std::nullopt, 12.5}, DescriptorVariant::kCeddLire, /*seed=*/9);
  const DescriptorValues expected = ExtractCedd(image, DescriptorVariant::kCeddLire).values;
  EXPECT_EQ(view.cedd(), std::string(expected.begin(), expected.end()));
  EXPECT_EQ(view.azimuth_deg(), 40.0);
  EXPECT_EQ(view.elevation_deg(), 12.5);
  ASSERT_TRUE(view.has_typical_distance());
  EXPECT_DOUBLE_EQ(view.typical_distance(),
                   DescribeView(image, DescriptorVariant::kCeddLire, 9).typical_distance);
  EXPECT_GT(view.typical_distance(), 0.0);
  EXPECT_LT(view.typical_distance(), 1.0);

  // With a region, everything is computed on the region alone, as if the device had cropped.
  const cv::Rect region(20, 30, 80, 70);
  const v1::View cropped =
      ComputeView({image, 40.0, region, std::nullopt}, DescriptorVariant::kCeddFull, 9);
  const cv::Mat crop = image(region).clone();
  const DescriptorValues crop_cedd = ExtractCedd(crop, DescriptorVariant::kCeddFull).values;
  EXPECT_EQ(cropped.cedd(), std::string(crop_cedd.begin(), crop_cedd.end()));
  EXPECT_DOUBLE_EQ(cropped.typical_distance(),
                   DescribeView(crop, DescriptorVariant::kCeddFull, 9).typical_distance);
  EXPECT_FALSE(cropped.has_elevation_deg());

  EXPECT_THROW(ComputeView({image, 0, cv::Rect(100, 100, 40, 40), {}},
                           DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
  EXPECT_THROW(ComputeView({cv::Mat(), 0, {}, {}}, DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace orbit
