#include "core/descriptor/distortion.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

const double kSin20 = std::sin(20 * std::numbers::pi / 180);
const double kCos20 = std::cos(20 * std::numbers::pi / 180);

// Sum of fspecial('motion',15,20)'s unnormalised taps, from an independent Python port of
// fspecial.m (every half-matrix value below is derived by hand in the test that uses it).
constexpr double kUnnormalisedSum = 15.212354042567148;

// fspecial('motion',15,20): the half matrix is dist(y, x) for y = 0..3, x = 0..7, with
// dist = 1 + eps - |y cos(20) - x sin(20)| (or the distance to the line's end point when the
// pixel lies beyond it), clipped at 0. Unfolded and flipped up-down, kernel(3 - y, 7 + x) and
// kernel(3 + y, 7 - x) both hold dist(y, x) / sum.
TEST(MotionBlurKernelTest, MatchesFspecialMotion15At20Degrees) {
  const cv::Mat k = MotionBlurKernel(15, 20);
  ASSERT_EQ(k.type(), CV_64FC1);
  ASSERT_EQ(k.rows, 7);
  ASSERT_EQ(k.cols, 15);
  const auto at = [&k](int r, int c) { return k.at<double>(r, c) * kUnnormalisedSum; };

  EXPECT_NEAR(at(3, 7), 1.0, 1e-12);                                 // (0,0): on the line
  EXPECT_NEAR(at(3, 8), 1 - kSin20, 1e-12);                          // (0,1): 0.658
  EXPECT_NEAR(at(3, 9), 1 - 2 * kSin20, 1e-12);                      // (0,2): 0.316
  EXPECT_EQ(k.at<double>(3, 10), 0);                                 // (0,3): 3 sin 20 > 1, outside
  EXPECT_NEAR(at(2, 7), 1 - kCos20, 1e-12);                          // (1,0): 0.060
  EXPECT_NEAR(at(2, 10), 1 - std::abs(kCos20 - 3 * kSin20), 1e-12);  // (1,3): 0.914
  EXPECT_NEAR(at(1, 13), 1 - std::abs(2 * kCos20 - 6 * kSin20), 1e-12);  // (2,6): 0.827
  // (3,7) lies beyond the end point (radius sqrt(58) >= 7): distance to the end point.
  const double d37 = 3 * kCos20 - 7 * kSin20;                           // 0.42494
  const double x37 = 7 - std::abs((7 + d37 * kSin20) / kCos20);         // -0.60393
  EXPECT_NEAR(at(0, 14), 1 - std::sqrt(d37 * d37 + x37 * x37), 1e-12);  // 0.26157
  EXPECT_NEAR(at(0, 14), 0.26157, 1e-5);
  // (2,7) also: 0.42245.
  const double d27 = 2 * kCos20 - 7 * kSin20;
  const double x27 = 7 - std::abs((7 + d27 * kSin20) / kCos20);
  EXPECT_NEAR(at(1, 14), 1 - std::sqrt(d27 * d27 + x27 * x27), 1e-12);

  // The line rises to the right: top-right and bottom-left corners set, the others empty.
  EXPECT_EQ(k.at<double>(0, 0), 0);
  EXPECT_EQ(k.at<double>(6, 14), 0);
  EXPECT_GT(k.at<double>(6, 0), 0);
  // Point-symmetric, normalised.
  for (int r = 0; r < 7; ++r) {
    for (int c = 0; c < 15; ++c) EXPECT_EQ(k.at<double>(r, c), k.at<double>(6 - r, 14 - c));
  }
  EXPECT_NEAR(cv::sum(k)[0], 1.0, 1e-12);
}

TEST(MotionBlurKernelTest, HorizontalAndVerticalLinesHaveTheRightShape) {
  // fspecial('motion', 5, 0) is [0.2 0.2 0.2 0.2 0.2]; at 90 degrees it is the same column.
  const cv::Mat horizontal = MotionBlurKernel(5, 0);
  ASSERT_EQ(horizontal.rows, 1);
  ASSERT_EQ(horizontal.cols, 5);
  for (int c = 0; c < 5; ++c) EXPECT_NEAR(horizontal.at<double>(0, c), 0.2, 1e-12);
  const cv::Mat vertical = MotionBlurKernel(5, 90);
  ASSERT_EQ(vertical.rows, 5);
  ASSERT_EQ(vertical.cols, 1);
  EXPECT_NEAR(vertical.at<double>(2, 0), 0.2, 1e-12);
  // 200 degrees is 20 degrees: fspecial takes the angle modulo 180.
  EXPECT_EQ(cv::norm(MotionBlurKernel(15, 200), MotionBlurKernel(15, 20), cv::NORM_INF), 0);
}

TEST(MotionBlurTest, SmearsAPointAlongTheLineRisingToTheRight) {
  cv::Mat image = cv::Mat::zeros(21, 31, CV_8UC1);
  const int cy = 10, cx = 15;
  image.at<std::uint8_t>(cy, cx) = 255;
  const cv::Mat blurred = MotionBlur(image);
  ASSERT_EQ(blurred.size(), image.size());
  ASSERT_EQ(blurred.type(), CV_8UC1);
  // out(cy + dy, cx + dx) = round(255 * kernel(3 - dy, 7 - dx)).
  EXPECT_EQ(blurred.at<std::uint8_t>(cy, cx), 17);         // 255 / 15.2124 = 16.76
  EXPECT_EQ(blurred.at<std::uint8_t>(cy, cx + 1), 11);     // 16.76 * 0.658 = 11.03
  EXPECT_EQ(blurred.at<std::uint8_t>(cy - 3, cx + 7), 4);  // 16.76 * 0.2616 = 4.38
  EXPECT_EQ(blurred.at<std::uint8_t>(cy + 3, cx - 7), 4);
  EXPECT_EQ(blurred.at<std::uint8_t>(cy + 3, cx + 7), 0);  // the other diagonal stays dark
  EXPECT_EQ(blurred.at<std::uint8_t>(cy - 3, cx - 7), 0);
}

TEST(MotionBlurTest, PadsWithZerosLikeImfilter) {
  const cv::Mat grey(20, 40, CV_8UC3, cv::Scalar(100, 100, 100));
  const cv::Mat blurred = MotionBlur(grey);
  // Far from the border every tap sees 100 and the kernel sums to 1.
  EXPECT_EQ(blurred.at<cv::Vec3b>(10, 20), cv::Vec3b(100, 100, 100));
  // At the top-left pixel only the taps at rows 3..6, columns 7..14 fall inside: dist(0,0),
  // dist(0,1), dist(0,2) and dist(1,0) = 1 + 0.658 + 0.316 + 0.060 = 2.0343, / 15.2124 = 0.1337.
  EXPECT_EQ(blurred.at<cv::Vec3b>(0, 0), cv::Vec3b(13, 13, 13));
}

TEST(MotionBlurTest, BlursEveryChannelOnItsOwn) {
  cv::Mat image(16, 16, CV_8UC3, cv::Scalar(0, 0, 0));
  image.at<cv::Vec3b>(8, 8) = cv::Vec3b(0, 255, 0);
  const cv::Mat blurred = MotionBlur(image);
  EXPECT_EQ(blurred.at<cv::Vec3b>(8, 8), cv::Vec3b(0, 17, 0));
  std::vector<cv::Mat> planes;
  cv::split(blurred, planes);
  EXPECT_EQ(cv::countNonZero(planes[0]), 0);
  EXPECT_EQ(cv::countNonZero(planes[2]), 0);
  EXPECT_GT(cv::countNonZero(planes[1]), 20);
}

// imfilter's definition, pixel by pixel and tap by tap in the kernel's row-major order: the
// blur must give these values to the last bit, whatever order its loops run in, for kernels of
// several lengths and angles and for images narrower than the kernel.
TEST(MotionBlurTest, EqualsTheCorrelationWithTheKernelValueByValue) {
  cv::RNG rng(5);
  for (const cv::Size size : {cv::Size(37, 23), cv::Size(5, 9)}) {
    for (const int channels : {1, 3}) {
      cv::Mat image(size, CV_8UC(channels));
      rng.fill(image, cv::RNG::UNIFORM, 0, 256);
      for (const auto& [length, angle] :
           std::vector<std::pair<double, double>>{{15, 20}, {9, 135}, {4.5, 90}, {21, 0}, {1, 0}}) {
        const cv::Mat kernel = MotionBlurKernel(length, angle);
        const cv::Mat blurred = MotionBlur(image, length, angle);
        int differing = 0;
        for (int y = 0; y < image.rows; ++y) {
          for (int x = 0; x < image.cols; ++x) {
            for (int ch = 0; ch < channels; ++ch) {
              double sum = 0;
              for (int r = 0; r < kernel.rows; ++r) {
                for (int c = 0; c < kernel.cols; ++c) {
                  const int yy = y + r - kernel.rows / 2, xx = x + c - kernel.cols / 2;
                  const double w = kernel.at<double>(r, c);
                  if (w == 0 || yy < 0 || yy >= image.rows || xx < 0 || xx >= image.cols) continue;
                  sum += w * image.ptr<std::uint8_t>(yy)[xx * channels + ch];
                }
              }
              differing += blurred.ptr<std::uint8_t>(y)[x * channels + ch] !=
                           cv::saturate_cast<std::uint8_t>(std::round(sum));
            }
          }
        }
        EXPECT_EQ(differing, 0) << size << " x" << channels << ", length " << length << ", angle "
                                << angle;
      }
    }
  }
}

TEST(MotionBlurTest, RejectsImagesItCannotBlur) {
  EXPECT_THROW(MotionBlur(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(MotionBlur(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(MotionBlurKernel(NAN, 20), std::invalid_argument);
}

TEST(AddGaussianNoiseTest, HasTheRequestedVarianceOnTheUnitScale) {
  const cv::Mat grey(256, 256, CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::Mat noisy = AddGaussianNoise(grey, 0.012, 7);
  ASSERT_EQ(noisy.type(), CV_8UC3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(noisy.reshape(1), mean, stddev);
  // sqrt(0.012) * 255 = 27.93 grey levels; 128 is 4.6 sigma from either clip, so clipping does
  // not shrink it. 196608 samples: the estimate is good to well under 1%.
  EXPECT_NEAR(stddev[0], std::sqrt(0.012) * 255, 0.3);
  EXPECT_NEAR(mean[0], 128, 0.3);
}

TEST(AddGaussianNoiseTest, ClipsToTheValidRange) {
  const cv::Mat white(64, 64, CV_8UC1, cv::Scalar(255));
  const cv::Mat noisy = AddGaussianNoise(white, 0.012, 3);
  // Half the noise pushes above 1 and is clipped to 255: about half the pixels stay white, and
  // the mean drops by sigma * phi(0) = 27.93 * 0.3989 = 11.1 grey levels.
  const double white_fraction = cv::countNonZero(noisy == 255) / 4096.0;
  EXPECT_NEAR(white_fraction, 0.5, 0.05);
  EXPECT_NEAR(cv::mean(noisy)[0], 255 - 11.14, 1.0);
}

TEST(AddGaussianNoiseTest, IsReproducibleFromTheSeed) {
  cv::Mat image(32, 32, CV_8UC3);
  cv::randu(image, 0, 256);
  const cv::Mat a = AddGaussianNoise(image, 0.012, 42);
  EXPECT_EQ(cv::norm(a, AddGaussianNoise(image, 0.012, 42), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(a, AddGaussianNoise(image, 0.012, 43), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(image, AddGaussianNoise(image, 0, 42), cv::NORM_INF), 0);
  EXPECT_THROW(AddGaussianNoise(image, -0.1, 1), std::invalid_argument);
  EXPECT_THROW(AddGaussianNoise(cv::Mat(), 0.012, 1), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
