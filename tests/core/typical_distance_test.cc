#include "core/typical_distance.h"

#include <array>
#include <stdexcept>

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/cedd.h"
#include "core/distortion.h"
#include "core/similarity.h"
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

TEST(TypicalDistanceTest, UsesTheMotionBlurredAndTheNoisyCopy) {
  const cv::Mat view = ReadImageFile((testing::DataDir() / "coil-100" / "obj1__0.png").string());
  const auto variant = DescriptorVariant::kCeddFull;
  const DescriptorValues original = ExtractCedd(view, variant).values;
  const double blurred =
      TanimotoDistance(original, ExtractCedd(MotionBlur(view, 15, 20), variant).values);
  const double noisy =
      TanimotoDistance(original, ExtractCedd(AddGaussianNoise(view, 0.012, 11), variant).values);
  EXPECT_GT(blurred, 0);
  EXPECT_GT(noisy, 0);
  EXPECT_NEAR(TypicalDistance(view, variant, 11), (blurred + noisy) / 2, 1e-15);

  const auto copies = TypicalDistortions(view, 11);
  EXPECT_EQ(cv::norm(copies[0], MotionBlur(view), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(copies[1], AddGaussianNoise(view, 0.012, 11), cv::NORM_INF), 0);
}

TEST(TypicalDistanceTest, DistortedCopiesStayCloserThanTheNextView) {
  // What the rejection rule relies on: a view's own distorted copies are nearer to it than a
  // view of another object is.
  const auto dir = testing::DataDir() / "coil-100";
  const cv::Mat view = ReadImageFile((dir / "obj1__0.png").string());
  const cv::Mat other = ReadImageFile((dir / "obj2__0.png").string());
  for (const auto variant : {DescriptorVariant::kCeddLire, DescriptorVariant::kCeddFull}) {
    const double typical = TypicalDistance(view, variant, 3);
    const double to_other = TanimotoDistance(ExtractCedd(view, variant).values,
                                             ExtractCedd(other, variant).values);
    EXPECT_LT(typical, to_other) << VariantName(variant);
    EXPECT_GT(typical, 0.01) << VariantName(variant);
  }
}

}  // namespace
}  // namespace orbit
