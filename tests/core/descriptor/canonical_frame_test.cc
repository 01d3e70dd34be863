// CanonicalFrame (core/descriptor/canonical_frame.h): its size, its blur against OpenCV's, its
// brightness rule on hand-computed colours, and what it is for: a frame's descriptor that stays
// put under gain and noise.
#include "core/descriptor/canonical_frame.h"

#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/distortion.h"
#include "core/descriptor/similarity.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

cv::Mat Coil(int object, int azimuth) {
  return ReadImageFile(testing::CoilDir() + "/obj" + std::to_string(object) + "__" +
                       std::to_string(azimuth) + ".png");
}

TEST(CanonicalFrameTest, ResamplesToAbout128x128KeepingTheAspectRatio) {
  // scale = sqrt(16384 / (w h)); sides rounded to the nearest pixel, at least 1.
  const auto size = [](int w, int h) {
    return CanonicalFrame(cv::Mat(h, w, CV_8UC3, cv::Scalar(0, 0, 0))).size();
  };
  EXPECT_EQ(size(128, 128), cv::Size(128, 128));
  EXPECT_EQ(size(256, 256), cv::Size(128, 128));
  EXPECT_EQ(size(640, 480), cv::Size(148, 111));  // scale 0.23094: 147.8 x 110.9
  EXPECT_EQ(size(64, 32), cv::Size(181, 91));     // scale 2.8284: 181.0 x 90.5
  EXPECT_EQ(size(1, 1), cv::Size(128, 128));
  EXPECT_EQ(size(1000, 1), cv::Size(4048, 4));  // scale 4.0477
}

TEST(CanonicalFrameTest, ScalesTheBrightestChannelsPercentileTo200) {
  // Uniform (B, G, R) = (50, 100, 150): blurring changes nothing, the brightest channel is 150
  // everywhere, so every channel is scaled by 200 / 150: 66.7 -> 67, 133.3 -> 133, 200.
  const cv::Mat frame = CanonicalFrame(cv::Mat(64, 64, CV_8UC3, cv::Scalar(50, 100, 150)));
  EXPECT_EQ(frame.at<cv::Vec3b>(0, 0), cv::Vec3b(67, 133, 200));
  EXPECT_EQ(frame.at<cv::Vec3b>(127, 64), cv::Vec3b(67, 133, 200));
  // The top 4 rows at 250, the rest at 100. The blur (radius 6) spreads the bright rows over
  // rows 0..9, 7.8% of the pixels, under 10%: the 90th percentile is 100, so the bulk goes to 200.
  cv::Mat mixed(128, 128, CV_8UC3, cv::Scalar::all(100));
  mixed.rowRange(0, 4).setTo(cv::Scalar::all(250));
  EXPECT_EQ(CanonicalFrame(mixed).at<cv::Vec3b>(100, 64), cv::Vec3b(200, 200, 200));
  // A black backdrop does not count: 3/4 black, 1/4 at 80 -> the object goes to 200.
  cv::Mat backdrop(128, 128, CV_8UC3, cv::Scalar::all(0));
  backdrop(cv::Rect(32, 32, 64, 64)).setTo(cv::Scalar(40, 80, 60));
  EXPECT_EQ(CanonicalFrame(backdrop).at<cv::Vec3b>(64, 64), cv::Vec3b(100, 200, 150));
  EXPECT_EQ(CanonicalFrame(backdrop).at<cv::Vec3b>(2, 2), cv::Vec3b(0, 0, 0));
}

TEST(CanonicalFrameTest, LeavesANearlyBlackFrameAlone) {
  const cv::Mat frame = CanonicalFrame(cv::Mat(128, 128, CV_8UC3, cv::Scalar(10, 20, 5)));
  EXPECT_EQ(frame.at<cv::Vec3b>(64, 64), cv::Vec3b(10, 20, 5));
}

TEST(CanonicalFrameTest, BlursExactlyAsOpenCVsGaussian) {
  // Step 2 is computed in its own integer arithmetic (canonical_frame.cc); it must stay OpenCV's
  // GaussianBlur of deviation 2 to the last bit, borders and small images included.
  cv::RNG random(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int width = 1 + random.uniform(0, 160), height = 1 + random.uniform(0, 160);
    cv::Mat image(height, width, CV_8UC3);
    random.fill(image, cv::RNG::UNIFORM, 0, 256);
    if (trial % 2 == 1) cv::threshold(image, image, 128, 255, cv::THRESH_BINARY);  // hard edges
    cv::Mat expected;
    cv::GaussianBlur(image, expected, cv::Size(0, 0), kCanonicalBlurSigma);
    const cv::Mat blurred = CanonicalFrame(
        image, {.area = 0, .blur_sigma = kCanonicalBlurSigma, .normalise_brightness = false});
    ASSERT_EQ(cv::norm(blurred, expected, cv::NORM_INF), 0) << width << "x" << height;
  }
}

TEST(CanonicalFrameTest, RefusesWhatItCannotPrepare) {
  EXPECT_THROW(CanonicalFrame(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(CanonicalFrame(cv::Mat(8, 8, CV_8UC1, cv::Scalar(1))), std::invalid_argument);
  EXPECT_THROW(CanonicalFrame(cv::Mat(8, 8, CV_32FC3, cv::Scalar::all(1))), std::invalid_argument);
}

// What the canonical frame is for, on real views: a dimmer exposure and sensor noise barely move
// cedd-robust, while they move cedd-full far (the noisy copy's texture classes carry noise).
TEST(CanonicalFrameTest, RobustDescriptorsStayPutUnderGainAndNoise) {
  for (const int object : {5, 42, 77}) {
    const cv::Mat view = Coil(object, 30);
    cv::Mat dim;
    view.convertTo(dim, -1, 0.6);
    const cv::Mat noisy = AddGaussianNoise(view, 0.012, 7);
    const auto similarity = [&](const cv::Mat& other, DescriptorVariant variant) {
      return Tanimoto(ExtractCedd(view, variant).values, ExtractCedd(other, variant).values);
    };
    EXPECT_GT(similarity(dim, DescriptorVariant::kCeddRobust), 0.9) << object;
    EXPECT_GT(similarity(noisy, DescriptorVariant::kCeddRobust), 0.8) << object;
    EXPECT_LT(similarity(noisy, DescriptorVariant::kCeddFull), 0.6) << object;
    EXPECT_GT(similarity(dim, DescriptorVariant::kCeddRobust),
              similarity(dim, DescriptorVariant::kCeddFull))
        << object;
  }
}

}  // namespace
}  // namespace orbit
