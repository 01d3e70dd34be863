// EstimateNoiseSigma (core/descriptor/noise_estimate.h) against images with known added noise.
#include "core/descriptor/noise_estimate.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/descriptor/distortion.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

// A flat grey image with N(0, sigma) added to every value, far from 0 and 255 so none is
// clipped: the estimate is within 3% of sigma (1 channel and 3; 256 x 256 values per channel).
TEST(NoiseEstimateTest, ReadsTheDeviationOfNoiseAddedToAFlatImage) {
  std::mt19937 random(5);
  for (const int channels : {1, 3}) {
    for (const double sigma : {2.0, 5.0, 10.0, 20.0}) {
      cv::Mat image(256, 256, CV_8UC(channels));
      std::normal_distribution<double> noise(0, sigma);
      for (int r = 0; r < image.rows; ++r) {
        auto* row = image.ptr<std::uint8_t>(r);
        for (int i = 0; i < image.cols * channels; ++i) {
          row[i] = cv::saturate_cast<std::uint8_t>(128 + noise(random));
        }
      }
      EXPECT_NEAR(EstimateNoiseSigma(image), sigma, 0.03 * sigma + 0.3)
          << channels << " channels, sigma " << sigma;
    }
  }
}

// A smooth ramp (a plane) reads as no noise at all: the mask cancels planes exactly.
TEST(NoiseEstimateTest, APlaneReadsAsNoNoise) {
  cv::Mat ramp(64, 64, CV_8UC1);
  for (int r = 0; r < 64; ++r) {
    for (int c = 0; c < 64; ++c) ramp.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(r + 2 * c);
  }
  EXPECT_EQ(EstimateNoiseSigma(ramp), 0.0);
  EXPECT_EQ(EstimateNoiseSigma(cv::Mat(2, 2, CV_8UC1, cv::Scalar(9))), 0.0);
  EXPECT_THROW(EstimateNoiseSigma(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(EstimateNoiseSigma(cv::Mat(8, 8, CV_32FC1)), std::invalid_argument);
}

// On COIL-100 views (objects on black) a clean view reads 1-2 grey levels, the protocol's noise
// (var 0.012: 27.9 grey levels per channel) 23-26 on obj1, obj47 and obj80 (the black
// background clips part of it), and the estimate grows with the noise added, staying between
// 0.75 and 1 times the deviation added (plus the clean view's reading); motion blur lowers it.
TEST(NoiseEstimateTest, OnCoilViewsItGrowsWithTheNoiseAdded) {
  for (const int object : {1, 47, 80}) {
    const cv::Mat view = cv::imread(
        (testing::DataDir() / "coil-100" / ("obj" + std::to_string(object) + "__0.png")).string());
    ASSERT_FALSE(view.empty());
    const double clean = EstimateNoiseSigma(view);
    EXPECT_LT(clean, 2.5) << "obj" << object;
    double previous = clean;
    for (const double variance : {0.002, 0.006, 0.012, 0.03}) {
      const double estimate = EstimateNoiseSigma(AddGaussianNoise(view, variance, 3));
      EXPECT_GT(estimate, previous + 2) << "obj" << object << ", var " << variance;
      EXPECT_LT(estimate, 255 * std::sqrt(variance) + clean)
          << "obj" << object << ", var " << variance;
      EXPECT_GT(estimate, 0.75 * 255 * std::sqrt(variance))
          << "obj" << object << ", var " << variance;
      previous = estimate;
    }
    EXPECT_LT(EstimateNoiseSigma(MotionBlur(view)), clean);
  }
}

}  // namespace
}  // namespace orbit
