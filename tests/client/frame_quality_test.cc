// Frame quality on the device (client/frame_quality.h): blurred and noisy frames are told from
// sharp, clean ones of the same scene.
#include "client/frame_quality.h"

#include <gtest/gtest.h>

#include "core/descriptor/distortion.h"
#include "tests/support/client_test_support.h"

namespace orbit {
namespace {

TEST(FrameQualityTest, BlurLowersSharpnessAndNoiseRaisesTheNoiseEstimate) {
  const cv::Mat image = testing::CoilImage(3, 0);
  const FrameQuality sharp = MeasureFrameQuality(image);
  const FrameQuality blurred = MeasureFrameQuality(MotionBlur(image));
  const FrameQuality noisy = MeasureFrameQuality(AddGaussianNoise(image, 0.01, 4));
  EXPECT_LT(blurred.sharpness, 0.35 * sharp.sharpness);
  EXPECT_LT(sharp.noise_sigma, 3);
  // Variance 0.01 of the [0, 1] range: a deviation of 25.5 grey levels, partly clipped on the
  // black background.
  EXPECT_GT(noisy.noise_sigma, 12);
  EXPECT_LT(noisy.noise_sigma, 26);
  // Blur reads on the same scale for every scene (core/descriptor/blur_estimate.h); noise reads as
  // sharp.
  EXPECT_LT(sharp.blur, 0.5);
  EXPECT_GT(blurred.blur, 0.6);
  EXPECT_LT(noisy.blur, sharp.blur);

  // A region is measured alone: a flat grey frame around the object changes nothing.
  cv::Mat framed(300, 400, CV_8UC3, cv::Scalar(90, 90, 90));
  image.copyTo(framed(cv::Rect(50, 60, 128, 128)));
  const FrameQuality region = MeasureFrameQuality(framed, cv::Rect(50, 60, 128, 128));
  EXPECT_DOUBLE_EQ(region.sharpness, sharp.sharpness);
  EXPECT_DOUBLE_EQ(region.noise_sigma, sharp.noise_sigma);
  EXPECT_DOUBLE_EQ(region.blur, sharp.blur);
  EXPECT_THROW(MeasureFrameQuality(framed, cv::Rect(350, 0, 100, 10)), std::invalid_argument);
  EXPECT_THROW(MeasureFrameQuality(cv::Mat()), std::invalid_argument);
}

TEST(FrameQualityTest, UsableFramesAreNotFarBelowTheMedianSharpnessNorNoisy) {
  const std::vector<FrameQuality> capture = {{100, 1}, {120, 1}, {30, 1}, {110, 2}, {90, 20}};
  // Median sharpness 100: frames below 35 are blurred.
  EXPECT_DOUBLE_EQ(MinUsableSharpness(capture), 35);
  EXPECT_TRUE(IsUsableFrame(capture[0], 35));
  EXPECT_FALSE(IsUsableFrame(capture[2], 35));  // blurred
  EXPECT_FALSE(IsUsableFrame(capture[4], 35));  // noisy
  EXPECT_DOUBLE_EQ(MinUsableSharpness({}), 0);
  const v1::FrameQuality proto = ToProtoFrameQuality({42.5, 3.25});
  EXPECT_EQ(proto.sharpness(), 42.5);
  EXPECT_EQ(proto.noise_sigma(), 3.25);
}

}  // namespace
}  // namespace orbit
