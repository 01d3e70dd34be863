#include "core/descriptor/typical_distance.h"

#include <array>
#include <stdexcept>

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/distortion.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

TEST(TypicalDistanceTest, IsTheMeanDistanceToTheCopies) {
  DescriptorValues view{}, same{}, empty{};
  view[0] = 7;
  view[30] = 2;
  same = view;
  // T(view, same) = 0; T(view, all zeros) = 1 (TC of one all-zero vector is 0).
  const std::array<DescriptorValues, 2> copies{same, empty};
  EXPECT_DOUBLE_EQ(TypicalDistance(view, copies), 0.5);
  // view . half = 7*3 + 2*1 = 23; TC = 23 / (53 + 10 - 23) = 0.575.
  DescriptorValues half{};
  half[0] = 3;
  half[30] = 1;
  const std::array<DescriptorValues, 1> one{half};
  EXPECT_DOUBLE_EQ(TypicalDistance(view, one), 1 - 23.0 / 40.0);
  EXPECT_THROW(TypicalDistance(view, std::span<const DescriptorValues>()), std::invalid_argument);
}

TEST(TypicalDistanceTest, TheCopiesAreTheProtocolsMotionBlurAndNoise) {
  const cv::Mat view = ReadImageFile((testing::DataDir() / "coil-100" / "obj1__0.png").string());
  const auto copies = TypicalDistortions(view, 11);
  EXPECT_EQ(cv::norm(copies[0], MotionBlur(view, 15, 20), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(copies[1], AddGaussianNoise(view, 0.012, 11), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(copies[1], AddGaussianNoise(view, 0.012, 12), cv::NORM_INF), 0);
}

}  // namespace
}  // namespace orbit
