// Behaviour of the CEDD extractor beyond the reference vectors: degenerate regions, the two
// variants, the three image types, regions of interest, errors, and the fast path against a
// literal transcription of docs/design.md#cedd on random images.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "client/image_file.h"
#include "core/descriptor/canonical_frame.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/cedd_colour.h"
#include "core/descriptor/cedd_quantisation.h"
#include "core/descriptor/cedd_texture.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

constexpr DescriptorVariant kLire = DescriptorVariant::kCeddLire;
constexpr DescriptorVariant kFull = DescriptorVariant::kCeddFull;

int Total(const DescriptorValues& v) {
  int sum = 0;
  for (auto x : v) sum += x;
  return sum;
}

cv::Mat Coil(int object, int azimuth) {
  return ReadImageFile((testing::DataDir() / "coil-100" /
                        ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
                           .string());
}

TEST(Cedd, RegionsOnePixelThinHaveNoLireBlocksAndGiveZeros) {
  for (const cv::Size size :
       {cv::Size(1, 1), cv::Size(1, 9), cv::Size(9, 1), cv::Size(1, 500), cv::Size(700, 1)}) {
    const cv::Mat image(size, CV_8UC3, cv::Scalar(30, 200, 90));
    const Descriptor d = ExtractCedd(image, kLire);
    EXPECT_EQ(Total(d.values), 0) << size;
  }
}

// A uniform pure red region: H = 0, S = 255, V = 255 fires only the fuzzy rule "red, saturated,
// bright" (10-bin red) and the 24-bin "normal" shade: colour bin 4, texture class 0 (no edge).
// The normalised histogram is 1 there, quantised to the top level 7; every other bin is 0.
TEST(Cedd, UniformRedGivesTheHandComputedDescriptor) {
  DescriptorValues expected{};
  expected[4] = 7;
  const cv::Mat red(128, 128, CV_8UC3, cv::Scalar(0, 0, 255));
  EXPECT_EQ(ExtractCedd(red, kLire).values, expected);
  EXPECT_EQ(ExtractCedd(red, kFull).values, expected);
  // cedd-full describes even a single pixel, and a one-pixel-thin strip.
  EXPECT_EQ(ExtractCedd(cv::Mat(1, 1, CV_8UC3, cv::Scalar(0, 0, 255)), kFull).values, expected);
  EXPECT_EQ(ExtractCedd(cv::Mat(1, 37, CV_8UC3, cv::Scalar(0, 0, 255)), kFull).values, expected);
}

TEST(Cedd, DescriptorIsTaggedWithItsVariant) {
  const cv::Mat image = Coil(3, 40);
  EXPECT_EQ(ExtractCedd(image, kLire).variant, kLire);
  EXPECT_EQ(ExtractCedd(image, kFull).variant, kFull);
}

// coil_like_128_outside80_modified.png differs from coil_like_128.png only outside the top-left
// 80x80 square that LIRE's grid reads on a 128x128 image. (The "inside" twin's change is too
// small to move any quantised bin, in LIRE's vectors as here.)
TEST(Cedd, FullVariantSeesPixelsThatLireIgnores) {
  const auto dir = testing::DataDir() / "cedd-conformance" / "synth";
  const cv::Mat base = ReadImageFile((dir / "coil_like_128.png").string());
  const cv::Mat outside = ReadImageFile((dir / "coil_like_128_outside80_modified.png").string());
  EXPECT_EQ(ExtractCedd(base, kLire), ExtractCedd(outside, kLire));
  EXPECT_NE(ExtractCedd(base, kFull), ExtractCedd(outside, kFull));
  // Painting over the ignored bottom-right 48 pixels changes cedd-full alone.
  cv::Mat painted = base.clone();
  painted(cv::Rect(80, 80, 48, 48)).setTo(cv::Scalar(255, 0, 0));
  EXPECT_EQ(ExtractCedd(painted, kLire), ExtractCedd(base, kLire));
  EXPECT_NE(ExtractCedd(painted, kFull), ExtractCedd(base, kFull));
}

TEST(Cedd, GreyBgrAndOpaqueBgraOfTheSameColoursAgree) {
  cv::Mat grey;
  cv::cvtColor(Coil(17, 120), grey, cv::COLOR_BGR2GRAY);
  cv::Mat bgr, bgra;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);  // alpha 255
  for (const DescriptorVariant v : {kLire, kFull}) {
    const Descriptor from_bgr = ExtractCedd(bgr, v);
    EXPECT_GT(Total(from_bgr.values), 0);
    EXPECT_EQ(ExtractCedd(grey, v), from_bgr);
    EXPECT_EQ(ExtractCedd(bgra, v), from_bgr);
  }
}

TEST(Cedd, TranslucentBgraIsCompositedOverBlack) {
  const cv::Mat colour = Coil(25, 200);
  cv::Mat bgra;
  cv::cvtColor(colour, bgra, cv::COLOR_BGR2BGRA);
  cv::Mat composited(colour.size(), CV_8UC3);
  for (int y = 0; y < colour.rows; ++y) {
    for (int x = 0; x < colour.cols; ++x) {
      const int alpha = (x * 7 + y * 3) % 256;
      bgra.at<cv::Vec4b>(y, x)[3] = static_cast<std::uint8_t>(alpha);
      for (int c = 0; c < 3; ++c) {
        // round(c * a / 255), by hand.
        const double exact = colour.at<cv::Vec3b>(y, x)[c] * alpha / 255.0;
        composited.at<cv::Vec3b>(y, x)[c] = static_cast<std::uint8_t>(std::lround(exact));
      }
    }
  }
  for (const DescriptorVariant v : {kLire, kFull}) {
    EXPECT_EQ(ExtractCedd(bgra, v), ExtractCedd(composited, v));
    EXPECT_NE(ExtractCedd(bgra, v), ExtractCedd(colour, v));
  }
}

TEST(Cedd, RegionOfInterestEqualsTheCroppedImage) {
  const cv::Mat image =
      ReadImageFile((testing::DataDir() / "cedd-conformance/synth/shapes_640x480.png").string());
  for (const cv::Rect roi : {cv::Rect(10, 20, 300, 200), cv::Rect(600, 0, 40, 480),
                             cv::Rect(0, 0, 640, 480), cv::Rect(5, 7, 3, 2)}) {
    for (const DescriptorVariant v : {kLire, kFull}) {
      EXPECT_EQ(ExtractCedd(image, v, roi), ExtractCedd(image(roi).clone(), v)) << roi;
    }
  }
}

// cedd-robust is cedd-full of the canonical frame, whatever the region's size or where it lies.
TEST(Cedd, RobustVariantIsFullOfTheCanonicalFrame) {
  const cv::Mat image =
      ReadImageFile((testing::DataDir() / "cedd-conformance/synth/shapes_640x480.png").string());
  const Descriptor robust = ExtractCedd(image, DescriptorVariant::kCeddRobust);
  EXPECT_EQ(robust.variant, DescriptorVariant::kCeddRobust);
  EXPECT_EQ(robust.values, ExtractCedd(CanonicalFrame(image), kFull).values);
  EXPECT_NE(robust.values, ExtractCedd(image, kFull).values);
  const cv::Rect roi(10, 20, 300, 200);
  EXPECT_EQ(ExtractCedd(image, DescriptorVariant::kCeddRobust, roi).values,
            ExtractCedd(CanonicalFrame(image(roi).clone()), kFull).values);
}

TEST(Cedd, RefusesWhatItCannotDescribe) {
  const cv::Mat image(50, 60, CV_8UC3, cv::Scalar::all(100));
  EXPECT_THROW(ExtractCedd(cv::Mat(), kLire), std::invalid_argument);
  EXPECT_THROW(ExtractCedd(image, kLire, cv::Rect(50, 40, 20, 20)), std::invalid_argument);
  EXPECT_THROW(ExtractCedd(image, kLire, cv::Rect(-1, 0, 10, 10)), std::invalid_argument);
  EXPECT_THROW(ExtractCedd(image, kFull, cv::Rect(0, 0, 0, 10)), std::invalid_argument);
  EXPECT_THROW(ExtractCedd(cv::Mat(8, 8, CV_32FC3), kLire), std::invalid_argument);
  EXPECT_THROW(ExtractCedd(cv::Mat(8, 8, CV_8UC2), kLire), std::invalid_argument);
}

// --- the fast path against a literal transcription of docs/design.md#cedd ------------------

// docs/design.md#cedd transcribed line by line for the LIRE grid: per-pixel double luminance
// summed per quadrant in row-major order, truncated means, integer mean colour. Shares only the
// colour and texture classification and the quantisation (covered by the reference vectors)
// with the product.
DescriptorValues LiteralLireCedd(const cv::Mat& bgr) {
  const int width = bgr.cols, height = bgr.rows, m = std::min(width, height);
  int n = -1;
  if (m >= 80) n = 1600;
  if (m < 80 && m >= 40) n = 400;
  int sx = 2, sy = 2, max_x, max_y;
  if (n > 0) {
    const int side = static_cast<int>(std::sqrt(n));
    sx = width / side;
    sy = height / side;
    if (sx % 2 != 0) --sx;
    if (sy % 2 != 0) --sy;
    max_x = sx * side;
    max_y = sy * side;
  } else {
    max_x = 2 * (width / 2);
    max_y = 2 * (height / 2);
  }
  double histogram[kCeddSize] = {};
  for (int y = 0; y < max_y; y += sy) {
    for (int x = 0; x < max_x; x += sx) {
      double area[4] = {0, 0, 0, 0};
      long sum_r = 0, sum_g = 0, sum_b = 0;
      for (int i = y; i < y + sy; ++i) {
        for (int j = x; j < x + sx; ++j) {
          const cv::Vec3b p = bgr.at<cv::Vec3b>(i, j);
          sum_b += p[0];
          sum_g += p[1];
          sum_r += p[2];
          const double luma = 0.114 * p[0] + 0.587 * p[1] + 0.299 * p[2];
          const bool left = j < x + sx / 2, top = i < y + sy / 2;
          area[(top ? 0 : 2) + (left ? 0 : 1)] += luma;
        }
      }
      for (double& a : area) a = static_cast<int>(a * (4.0 / (sx * sy)));
      const auto texture = cedd::ClassifyTexture({area[0], area[1], area[2], area[3]});
      const auto colour = cedd::FuzzyColour(static_cast<int>(sum_r / (sx * sy)),
                                            static_cast<int>(sum_g / (sx * sy)),
                                            static_cast<int>(sum_b / (sx * sy)));
      for (int t = 0; t < texture.count; ++t) {
        for (int k = 0; k < kColourBins; ++k) {
          if (colour[k] > 0) histogram[kColourBins * texture.classes[t] + k] += colour[k];
        }
      }
    }
  }
  return cedd::Quantise(histogram);
}

// Random images built to hit the fast path's hard cases: flat patches and grey pixels make
// quadrant means exact integers (where the reference's rounding decides), noise makes the rest.
cv::Mat RandomImage(std::mt19937& rng) {
  std::uniform_int_distribution<int> side(2, 260), byte(0, 255), kind(0, 3);
  cv::Mat image(side(rng), side(rng), CV_8UC3);
  const int style = kind(rng);
  const cv::Vec3b flat(static_cast<std::uint8_t>(byte(rng)), static_cast<std::uint8_t>(byte(rng)),
                       static_cast<std::uint8_t>(byte(rng)));
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      cv::Vec3b& p = image.at<cv::Vec3b>(y, x);
      const auto b = static_cast<std::uint8_t>(byte(rng));
      switch (style) {
        case 0:
          p = cv::Vec3b(b, static_cast<std::uint8_t>(byte(rng)),
                        static_cast<std::uint8_t>(byte(rng)));
          break;
        case 1: p = cv::Vec3b(b, b, b); break;                                      // grey
        case 2: p = ((x / 7 + y / 5) % 3 == 0) ? cv::Vec3b(b, b, b) : flat; break;  // patches
        default:
          p = (x < image.cols / 2) == (y < image.rows / 3) ? flat : cv::Vec3b(0, 0, 0);
          break;
      }
    }
  }
  return image;
}

TEST(Cedd, FastPathEqualsTheLiteralAlgorithmOnRandomImages) {
  std::mt19937 rng(20261121);
  for (int trial = 0; trial < 300; ++trial) {
    const cv::Mat image = RandomImage(rng);
    ASSERT_EQ(ExtractCedd(image, kLire).values, LiteralLireCedd(image))
        << "trial " << trial << ", " << image.cols << "x" << image.rows;
  }
}

}  // namespace
}  // namespace orbit
