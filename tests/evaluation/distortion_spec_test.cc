// Query distortion specs (evaluation/distortion_spec.h): the protocol's names keep their
// meaning, parameterised steps combine, every malformed spec is refused naming its token, and
// each step does to an image what its name says.
#include "evaluation/distortion_spec.h"

#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/descriptor/distortion.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using Kind = DistortionStep::Kind;

std::string ErrorOf(const std::string& text) {
  try {
    ParseDistortionSpec(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

cv::Mat CoilImage() {
  return cv::imread((testing::DataDir() / "coil-100" / "obj1__0.png").string(), cv::IMREAD_COLOR);
}

TEST(DistortionSpecTest, TheProtocolsNamesKeepTheirMeaning) {
  EXPECT_TRUE(ParseDistortionSpec("df").steps.empty());
  EXPECT_EQ(ParseDistortionSpec("df").name, "df");
  const DistortionSpec mb = ParseDistortionSpec("mb");
  ASSERT_EQ(mb.steps.size(), 1u);
  EXPECT_EQ(mb.steps[0], (DistortionStep{Kind::kMotionBlur, 15, 20}));
  EXPECT_EQ(ParseDistortionSpec("mb:len=15:angle=20"), mb);
  EXPECT_EQ(ParseDistortionSpec("mb:angle=20"), mb);
  const DistortionSpec gn = ParseDistortionSpec("gn");
  EXPECT_EQ(gn.steps, (std::vector<DistortionStep>{{Kind::kGaussianNoise, 0.012, 0}}));
  EXPECT_EQ(ParseDistortionSpec("gn:var=0.012").name, "gn");
}

TEST(DistortionSpecTest, ParameterisedStepsCombineInOrderUnderACanonicalName) {
  const DistortionSpec spec = ParseDistortionSpec("mb:angle=70:len=9+gn:var=0.004");
  EXPECT_EQ(spec.name, "mb:len=9:angle=70+gn:var=0.004");
  EXPECT_EQ(spec.steps, (std::vector<DistortionStep>{{Kind::kMotionBlur, 9, 70},
                                                     {Kind::kGaussianNoise, 0.004, 0}}));
  EXPECT_EQ(ParseDistortionSpec("jpeg:q=20+gain:0.6+lowres:0.5").name,
            "jpeg:q=20+gain:0.6+lowres:0.5");
  EXPECT_EQ(ParseDistortionSpec("gain:1.4").steps[0], (DistortionStep{Kind::kGain, 1.4, 0}));
}

TEST(DistortionSpecTest, MalformedSpecsAreRefusedNamingTheToken) {
  EXPECT_THAT(ErrorOf("mb:len=0"), HasSubstr("'mb:len=0': len must be in [1, 100]"));
  EXPECT_THAT(ErrorOf("blur"),
              HasSubstr("'blur': unknown kind 'blur' (df, mb, gn, jpeg, gain, lowres)"));
  EXPECT_THAT(ErrorOf("gn:var=abc"),
              HasSubstr("'gn:var=abc': var must be a number in (0, 1], not 'abc'"));
  EXPECT_THAT(ErrorOf("gn:var=0"), HasSubstr("var must be in (0, 1]"));
  EXPECT_THAT(ErrorOf("gn:var=nan"), HasSubstr("var must be a number"));
  EXPECT_THAT(ErrorOf("jpeg"), HasSubstr("'jpeg': needs q=Q"));
  EXPECT_THAT(ErrorOf("jpeg:q=20.5"), HasSubstr("q must be a whole number in [1, 100]"));
  EXPECT_THAT(ErrorOf("gain"), HasSubstr("'gain': needs one value, e.g. gain:0.6"));
  EXPECT_THAT(ErrorOf("lowres:1"), HasSubstr("'lowres:1': lowres must be in (0, 1)"));
  EXPECT_THAT(ErrorOf("mb:len=9:len=10"), HasSubstr("len is given twice"));
  EXPECT_THAT(ErrorOf("mb:speed=3"), HasSubstr("unknown parameter 'speed=3' (len=, angle=)"));
  EXPECT_THAT(ErrorOf("mb+"), HasSubstr("distortion '': empty step"));
  EXPECT_THAT(ErrorOf("df+mb"), HasSubstr("'df+mb': df means no distortion"));
  EXPECT_THAT(ErrorOf(""), HasSubstr("empty"));
}

TEST(DistortionSpecTest, TheProtocolsDistortionsAreExactlyCoresFunctions) {
  const cv::Mat image = CoilImage();
  ASSERT_FALSE(image.empty());
  const auto same = [](const cv::Mat& a, const cv::Mat& b) {
    return cv::norm(a, b, cv::NORM_INF) == 0;
  };
  EXPECT_TRUE(same(ApplyDistortion(image, ParseDistortionSpec("df"), 7), image));
  EXPECT_TRUE(same(ApplyDistortion(image, ParseDistortionSpec("mb"), 7), MotionBlur(image)));
  EXPECT_TRUE(same(ApplyDistortion(image, ParseDistortionSpec("gn"), 7),
                   AddGaussianNoise(image, 0.012, 7)));
  EXPECT_TRUE(same(ApplyDistortion(image, ParseDistortionSpec("mb:len=9:angle=70+gn:var=0.004"), 7),
                   AddGaussianNoise(MotionBlur(image, 9, 70), 0.004, 7)));
}

TEST(DistortionSpecTest, GainLowResolutionAndJpegDoWhatTheySay) {
  // gain: 200 x 0.5 = 100; 200 x 1.4 = 280, clamped to 255.
  const cv::Mat grey(4, 4, CV_8UC1, cv::Scalar(200));
  EXPECT_EQ(ApplyDistortion(grey, ParseDistortionSpec("gain:0.5"), 1).at<std::uint8_t>(2, 2), 100);
  EXPECT_EQ(ApplyDistortion(grey, ParseDistortionSpec("gain:1.4"), 1).at<std::uint8_t>(2, 2), 255);

  // lowres:0.5 of a one-pixel checkerboard of 0 and 255 averages each 2 x 2 block to 127.5,
  // so the detail is gone: every pixel becomes 127 or 128.
  cv::Mat checker(8, 8, CV_8UC1);
  for (int r = 0; r < 8; ++r) {
    for (int c = 0; c < 8; ++c) checker.at<std::uint8_t>(r, c) = (r + c) % 2 == 0 ? 0 : 255;
  }
  double low = 0, high = 0;
  cv::minMaxLoc(ApplyDistortion(checker, ParseDistortionSpec("lowres:0.5"), 1), &low, &high);
  EXPECT_GE(low, 127);
  EXPECT_LE(high, 128);

  // JPEG: the lower the quality, the further from the original (mean absolute difference per
  // value).
  const cv::Mat image = CoilImage();
  const auto error = [&](const char* spec) {
    return cv::norm(ApplyDistortion(image, ParseDistortionSpec(spec), 1), image, cv::NORM_L1) /
           static_cast<double>(image.total() * image.channels());
  };
  // On COIL-100's obj1 at 0 degrees: 1.9, 4.3 and 8.2 grey levels (chroma subsampling costs
  // even q = 95 about 2).
  EXPECT_LT(error("jpeg:q=95"), 3.0);
  EXPECT_LT(error("jpeg:q=95"), error("jpeg:q=50"));
  EXPECT_LT(error("jpeg:q=50"), error("jpeg:q=10"));
  EXPECT_GT(error("jpeg:q=10"), 6.0);
  EXPECT_THROW(ApplyDistortion(cv::Mat(4, 4, CV_8UC4, cv::Scalar::all(9)),
                               ParseDistortionSpec("jpeg:q=50"), 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace orbit
