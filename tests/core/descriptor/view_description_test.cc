// DescribeView and its seed rule (core/descriptor/view_description.h): the numbers every enrollment
// path stores for a view image.
#include "core/descriptor/view_description.h"

#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/distortion.h"
#include "core/descriptor/similarity.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

cv::Mat Coil(const std::string& file) {
  return ReadImageFile((testing::DataDir() / "coil-100" / file).string());
}

TEST(ViewDescriptionTest, SeedRuleIsFnv1aOfTheDescriptorMixedWithTheBase) {
  // Expected values computed by hand with an independent script: FNV-1a 64 over the 144
  // values, then MixSeed(base, hash) (core/base/seeded_random.h). Pinned, so that a change of the
  // rule (or a platform-dependent hash) fails here.
  DescriptorValues zeros{};
  EXPECT_EQ(ViewNoiseSeed(zeros), 0x5abfb05278cb9f35ULL);
  DescriptorValues view{};
  view[0] = 7;
  view[30] = 2;
  EXPECT_EQ(ViewNoiseSeed(view, 1), 0x03ab660a4f2a0007ULL);
  EXPECT_EQ(ViewNoiseSeed(view, 5), 0x0186e0672c5ac8d4ULL);
}

TEST(ViewDescriptionTest, IsTheCeddAndTypicalDistanceOverTheSeededCopies) {
  const cv::Mat view = Coil("obj1__0.png");
  for (const auto variant : {DescriptorVariant::kCeddLire, DescriptorVariant::kCeddFull}) {
    const ViewDescription described = DescribeView(view, variant, /*base_seed=*/3);
    const DescriptorValues original = ExtractCedd(view, variant).values;
    EXPECT_EQ(described.descriptor, original);
    const std::uint64_t seed = ViewNoiseSeed(original, 3);
    const DescriptorValues blurred = ExtractCedd(MotionBlur(view, 15, 20), variant).values;
    const DescriptorValues noisy = ExtractCedd(AddGaussianNoise(view, 0.012, seed), variant).values;
    EXPECT_EQ(described.distorted[0], blurred);
    EXPECT_EQ(described.distorted[1], noisy);
    const double expected =
        (TanimotoDistance(original, blurred) + TanimotoDistance(original, noisy)) / 2;
    EXPECT_NEAR(described.typical_distance, expected, 1e-15) << VariantName(variant);
    EXPECT_GT(described.typical_distance, 0.01);
    // Another base seed draws other noise.
    EXPECT_NE(DescribeView(view, variant, 4).distorted[1], noisy);
  }
}

TEST(ViewDescriptionTest, SameImageSameNumbersWhateverElseDiffers) {
  // The seed comes from the view alone: a copy of the image (another buffer, a crop of a larger
  // canvas) is described identically.
  const cv::Mat view = Coil("obj5__40.png");
  cv::Mat canvas(view.rows + 20, view.cols + 30, view.type(), cv::Scalar(9, 9, 9));
  view.copyTo(canvas(cv::Rect(30, 20, view.cols, view.rows)));
  const ViewDescription a = DescribeView(view, DescriptorVariant::kCeddLire);
  const ViewDescription b =
      DescribeView(canvas(cv::Rect(30, 20, view.cols, view.rows)), DescriptorVariant::kCeddLire);
  EXPECT_EQ(a.descriptor, b.descriptor);
  EXPECT_EQ(a.distorted, b.distorted);
  EXPECT_EQ(a.typical_distance, b.typical_distance);
}

TEST(ViewDescriptionTest, DistortedCopiesStayCloserThanAnotherObject) {
  // What the rejection rule relies on: a view's own distorted copies are nearer to it than a
  // view of another object is.
  const cv::Mat view = Coil("obj1__0.png");
  const cv::Mat other = Coil("obj2__0.png");
  for (const auto variant : {DescriptorVariant::kCeddLire, DescriptorVariant::kCeddFull}) {
    const double typical = DescribeView(view, variant).typical_distance;
    const double to_other =
        TanimotoDistance(ExtractCedd(view, variant).values, ExtractCedd(other, variant).values);
    EXPECT_LT(typical, to_other) << VariantName(variant);
    EXPECT_GT(typical, 0.01) << VariantName(variant);
  }
}

TEST(ViewDescriptionTest, RefusesAnEmptyImage) {
  EXPECT_THROW(DescribeView(cv::Mat(), DescriptorVariant::kCeddLire), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
