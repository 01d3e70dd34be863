// EstimateBlur (core/descriptor/blur_estimate.h): by hand on patterns whose re-blurred variation is
// known, and on COIL-100 views, where motion blur of any direction raises it and noise lowers it.
#include "core/descriptor/blur_estimate.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "client/image_file.h"
#include "core/descriptor/distortion.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

TEST(BlurEstimateTest, ByHandOnStripesAndRamps) {
  // Nothing varies: nothing to judge.
  EXPECT_EQ(EstimateBlur(cv::Mat(20, 20, CV_8UC1, cv::Scalar(128))), 0);
  // Columns 0, 255, 0, ...: every horizontal neighbour differs by 255. Re-blurred over 9
  // columns, inner pixels alternate between 4 and 5 bright columns of 9 (113 and 142, a
  // difference of 28 or 29), so about 89% of the variation is lost: blur about 0.11. Rows do
  // not vary at all.
  cv::Mat stripes(40, 40, CV_8UC1);
  for (int x = 0; x < stripes.cols; ++x) stripes.col(x).setTo(x % 2 == 0 ? 0 : 255);
  EXPECT_NEAR(EstimateBlur(stripes), 0.11, 0.01);
  // A linear ramp (x per column) is as blurred as can be: the re-blurred ramp keeps its slope
  // inside, so no variation is lost (the border, replicated, loses a little).
  cv::Mat ramp(40, 64, CV_8UC1);
  for (int x = 0; x < ramp.cols; ++x) ramp.col(x).setTo(4 * x);
  EXPECT_GT(EstimateBlur(ramp), 0.85);
  // The larger of the two axes: the same stripes turned by 90 degrees read the same.
  EXPECT_DOUBLE_EQ(EstimateBlur(stripes.t()), EstimateBlur(stripes));
}

TEST(BlurEstimateTest, ColourAlphaAndBadImages) {
  const cv::Mat view = ReadImageFile((testing::DataDir() / "coil-100" / "obj5__40.png").string());
  cv::Mat with_alpha, grey;
  cv::cvtColor(view, with_alpha, cv::COLOR_BGR2BGRA);
  cv::cvtColor(view, grey, cv::COLOR_BGR2GRAY);
  EXPECT_DOUBLE_EQ(EstimateBlur(with_alpha), EstimateBlur(view));
  EXPECT_DOUBLE_EQ(EstimateBlur(grey), EstimateBlur(view));
  EXPECT_EQ(EstimateBlur(cv::Mat(1, 30, CV_8UC3, cv::Scalar(1, 2, 3))), 0);
  EXPECT_THROW(EstimateBlur(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(EstimateBlur(cv::Mat(8, 8, CV_32FC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(EstimateBlur(cv::Mat(8, 8, CV_8UC2, cv::Scalar(0))), std::invalid_argument);
}

TEST(BlurEstimateTest, OnCoilViewsMotionBlurRaisesItAndNoiseLowersIt) {
  for (const int object : {1, 23, 47, 88}) {
    const cv::Mat view = ReadImageFile(
        (testing::DataDir() / "coil-100" / ("obj" + std::to_string(object) + "__90.png")).string());
    const double sharp = EstimateBlur(view);
    EXPECT_LT(sharp, 0.55) << object;
    for (const double angle : {0.0, 45.0, 90.0, 160.0}) {
      EXPECT_GT(EstimateBlur(MotionBlur(view, 15, angle)), sharp + 0.15)
          << object << " at " << angle;
    }
    EXPECT_LT(EstimateBlur(AddGaussianNoise(view, 0.01, 7)), sharp) << object;
  }
}

}  // namespace
}  // namespace orbit
