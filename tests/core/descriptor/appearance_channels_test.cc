// The appearance channels of cedd-hsv-hog and cedd-hsv-layout
// (core/descriptor/appearance_channels.h): the bins of
// hand-made images worked out by hand, and what they are for: real look-alike objects that CEDD
// confuses told apart (eth-80-dev's apples, cars, cows and cups, each cropped to its box).
#include "core/descriptor/appearance_channels.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "client/image_file.h"
#include "core/descriptor/canonical_frame.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/distortion.h"
#include "core/descriptor/similarity.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

DescriptorValues Channels(const cv::Mat& image,
                          DescriptorVariant variant = DescriptorVariant::kCeddHsvHog) {
  DescriptorValues values{};
  AddAppearanceChannels(CanonicalFrame(image), variant, values);
  return values;
}

int Sum(const DescriptorValues& values, int first, int count) {
  int sum = 0;
  for (int i = first; i < first + count; ++i) sum += values[i];
  return sum;
}

TEST(AppearanceChannelsTest, AFlatColourFillsOneColourBinAndNoGradient) {
  // Pure red (BGR 0,0,255): the canonical frame scales it to 200 (its 90th percentile); OpenCV's
  // HSV gives hue 0, saturation 255, value 200: bins hue 0, saturation 3, value 3 (200 * 4 / 256)
  // -> (0 * 4 + 3) * 4 + 3 = 15. One bin holds the whole norm 24, clipped to 7.
  const DescriptorValues red = Channels(cv::Mat(100, 80, CV_8UC3, cv::Scalar(0, 0, 255)));
  for (int i = 0; i < kColourChannelSize; ++i) {
    EXPECT_EQ(red[kColourChannelOffset + i], i == 15 ? 7 : 0) << "colour bin " << i;
  }
  EXPECT_EQ(Sum(red, kGradientChannelOffset, kGradientChannelSize), 0);
  EXPECT_EQ(Sum(red, 0, kCeddSize), 0) << "CEDD's values are not touched";

  // Pure green (0,255,0): hue 60 -> bin 60 * 12 / 180 = 4 -> (4 * 4 + 3) * 4 + 3 = 79.
  const DescriptorValues green = Channels(cv::Mat(50, 50, CV_8UC3, cv::Scalar(0, 255, 0)));
  EXPECT_EQ(green[kColourChannelOffset + 79], 7);
  EXPECT_EQ(Sum(green, kColourChannelOffset, kColourChannelSize), 7);
}

TEST(AppearanceChannelsTest, StripesFillTheirOrientationsBins) {
  // Vertical stripes have horizontal gradients (angle 0), split between the bins centred at
  // 10 and 170 degrees (0 and 8); horizontal stripes have vertical ones (90 degrees), bin 4.
  cv::Mat vertical(128, 128, CV_8UC3), horizontal(128, 128, CV_8UC3);
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      vertical.at<cv::Vec3b>(y, x) = (x / 8) % 2 ? cv::Vec3b(200, 200, 200) : cv::Vec3b(40, 40, 40);
      horizontal.at<cv::Vec3b>(y, x) =
          (y / 8) % 2 ? cv::Vec3b(200, 200, 200) : cv::Vec3b(40, 40, 40);
    }
  }
  const DescriptorValues v = Channels(vertical), h = Channels(horizontal);
  for (int cell = 0; cell < kGradientCellsPerSide * kGradientCellsPerSide; ++cell) {
    const int first = kGradientChannelOffset + cell * kGradientOrientations;
    for (int bin = 0; bin < kGradientOrientations; ++bin) {
      if (bin == 0 || bin == 8) {
        EXPECT_GT(v[first + bin], 0) << "cell " << cell << " bin " << bin;
      } else {
        EXPECT_EQ(v[first + bin], 0) << "cell " << cell << " bin " << bin;
      }
      EXPECT_EQ(h[first + bin] > 0, bin == 4) << "cell " << cell << " bin " << bin;
    }
    EXPECT_EQ(v[first], v[first + 8]) << "an angle of 0 is halfway between bins 0 and 8";
  }
  // Same colours, same colour channel: only the gradients tell the two apart.
  EXPECT_TRUE(std::equal(v.begin() + kColourChannelOffset,
                         v.begin() + kColourChannelOffset + kColourChannelSize,
                         h.begin() + kColourChannelOffset));
}

// A 128x128 frame of `background` with a 64x64 square of `object` in its centre.
cv::Mat SquareOn(const cv::Scalar& object, const cv::Scalar& background) {
  cv::Mat frame(128, 128, CV_8UC3, background);
  frame(cv::Rect(32, 32, 64, 64)).setTo(object);
  return frame;
}

TEST(AppearanceChannelsTest, TheBackgroundAroundTheObjectIsNotCounted) {
  // A red square on green and on blue. The canonical frame scales every channel by 200 / 255;
  // red is then bin 15, green bin 79 and blue bin 143 ((8 * 4 + 3) * 4 + 3). The border ring is
  // background alone, green or blue; its colour covers about three quarters of the frame, all of
  // it the background's, so its bin is emptied (counted, it would hold the channel's largest
  // value, 7), and the square's gradients are counted only on its own side of the outline.
  const cv::Scalar red(0, 0, 255), green(0, 255, 0), blue(255, 0, 0);
  const DescriptorValues on_green = Channels(SquareOn(red, green));
  const DescriptorValues on_blue = Channels(SquareOn(red, blue));
  EXPECT_EQ(on_green[kColourChannelOffset + 15], 7);
  EXPECT_EQ(on_green[kColourChannelOffset + 79], 0);
  EXPECT_EQ(on_blue[kColourChannelOffset + 15], 7);
  EXPECT_EQ(on_blue[kColourChannelOffset + 143], 0);
  EXPECT_GT(Sum(on_green, kGradientChannelOffset, kGradientChannelSize), 0) << "the outline stays";
  // The rest of the channel is the square and its outline, where the blur mixes red with the
  // background: a red square on blue differs from one on green there alone.
  int same = 0;
  for (int i = 0; i < kColourChannelSize; ++i) {
    same += on_green[kColourChannelOffset + i] > 0 && on_blue[kColourChannelOffset + i] > 0;
  }
  EXPECT_EQ(same, 1) << "red's bin alone is in both";
}

TEST(AppearanceChannelsTest, DarkPixelsAndAnObjectOfTheRingsColoursAreKept) {
  // Dark pixels carry no colour to tell an object from its background: a red square on black
  // keeps black's bin 0 beside red's.
  const DescriptorValues on_black = Channels(SquareOn(cv::Scalar(0, 0, 255), cv::Scalar(0, 0, 0)));
  EXPECT_GT(on_black[kColourChannelOffset + 0], 0);
  EXPECT_EQ(on_black[kColourChannelOffset + 15], 7);
  // A frame of one colour, ring and all: the background is taken to cover at most
  // kMaxBackgroundShare of the frame, so the colour is kept, not emptied.
  const DescriptorValues flat = Channels(cv::Mat(96, 96, CV_8UC3, cv::Scalar(0, 255, 0)));
  EXPECT_EQ(flat[kColourChannelOffset + 79], 7);
}

TEST(AppearanceChannelsTest, RefusesAnImageThatIsNotBgrAndAVariantWithoutChannels) {
  DescriptorValues values{};
  constexpr DescriptorVariant kHog = DescriptorVariant::kCeddHsvHog;
  EXPECT_THROW(AddAppearanceChannels(cv::Mat(), kHog, values), std::invalid_argument);
  EXPECT_THROW(AddAppearanceChannels(cv::Mat(8, 8, CV_8UC1, cv::Scalar(9)), kHog, values),
               std::invalid_argument);
  EXPECT_THROW(AddAppearanceChannels(cv::Mat(8, 8, CV_8UC3, cv::Scalar(9, 9, 9)),
                                     DescriptorVariant::kCeddRobust, values),
               std::invalid_argument);
}

// A 128x128 frame, `upper` above `lower`.
cv::Mat Halves(const cv::Scalar& upper, const cv::Scalar& lower) {
  cv::Mat frame(128, 128, CV_8UC3, lower);
  frame(cv::Rect(0, 0, 128, 64)).setTo(upper);
  return frame;
}

TEST(AppearanceChannelsTest, TheColourLayoutTellsWhichColourIsAbove) {
  // Red above blue and blue above red hold the same colours and the same edge (unsigned
  // gradients): cedd-hsv-hog cannot tell them apart. In the layout, red is bin 7 (hue 0 -> 0,
  // saturation 255 -> 1, value 200 after the canonical frame's brightness -> 3: (0 * 2 + 1) * 4
  // + 3) and blue bin 71 (hue 120 -> 8: (8 * 2 + 1) * 4 + 3), in the upper half's 96 values or
  // the lower half's.
  const cv::Scalar red(0, 0, 255), blue(255, 0, 0);
  const cv::Mat red_above = Halves(red, blue), blue_above = Halves(blue, red);
  EXPECT_EQ(Channels(red_above), Channels(blue_above));
  constexpr auto kLayout = DescriptorVariant::kCeddHsvLayout;
  const DescriptorValues a = Channels(red_above, kLayout), b = Channels(blue_above, kLayout);
  constexpr int kUpper = kLayoutOffset, kLower = kLayoutOffset + kLayoutBandSize;
  EXPECT_GT(a[kUpper + 7], 0);
  EXPECT_EQ(a[kUpper + 71], 0);
  EXPECT_GT(a[kLower + 71], 0);
  EXPECT_EQ(a[kLower + 7], 0);
  EXPECT_EQ(b[kUpper + 71], a[kUpper + 7]);
  EXPECT_EQ(b[kLower + 7], a[kLower + 71]);
  EXPECT_EQ(b[kUpper + 7], 0);
  // The gradient cells are cedd-hsv-hog's, unchanged.
  EXPECT_TRUE(std::equal(a.begin() + kGradientChannelOffset, a.end(),
                         Channels(red_above).begin() + kGradientChannelOffset));
  EXPECT_LT(Tanimoto(a, b), 0.9);
}

// The colour channel's 192 values of `values` (the histogram's, or the layout's in its place),
// every other value 0.
DescriptorValues ColourChannelOnly(const DescriptorValues& values) {
  DescriptorValues layout{};
  std::copy_n(values.begin() + kLayoutOffset, kColourChannelSize, layout.begin() + kLayoutOffset);
  return layout;
}

TEST(AppearanceChannelsTest, TheColourLayoutDoesNotCountTheDarkGroundItsBoxHolds) {
  // Red above blue, framed tightly, and the same object in a box a quarter of whose height above
  // and below is a black ground (COIL-100's, or a shadow): the halves hold the same colours in
  // the same proportions, so the layouts agree but for the blurred edge from the black to the
  // red, a darker red (bin 6: value 2). Every bin present clips at 7, so the coefficient is 4
  // bins shared of 5 present, 0.8; counting the black in each half's dark bin, 4 of 7.
  const cv::Scalar red(0, 0, 255), blue(255, 0, 0);
  const cv::Mat tight = Halves(red, blue);
  cv::Mat framed(128, 128, CV_8UC3, cv::Scalar(0, 0, 0));
  framed(cv::Rect(0, 32, 128, 32)).setTo(red);
  framed(cv::Rect(0, 64, 128, 32)).setTo(blue);
  constexpr auto kLayout = DescriptorVariant::kCeddHsvLayout;
  const DescriptorValues a = Channels(tight, kLayout), b = Channels(framed, kLayout);
  constexpr int kUpper = kLayoutOffset, kLower = kLayoutOffset + kLayoutBandSize;
  EXPECT_EQ(b[kUpper + 0], 0);  // hue 0, saturation 0, value 0: the dark bin
  EXPECT_EQ(b[kLower + 0], 0);
  EXPECT_EQ(b[kUpper + 7], a[kUpper + 7]);    // red above (bins as in the test above)
  EXPECT_EQ(b[kLower + 71], a[kLower + 71]);  // blue below
  EXPECT_EQ(b[kUpper + 6], 7);
  EXPECT_NEAR(Tanimoto(ColourChannelOnly(a), ColourChannelOnly(b)), 0.8, 1e-6);
}

TEST(AppearanceChannelsTest, TwoRedsThatCeddCallsOneAreTwoHere) {
  // A red and a purplish red: CEDD's fuzzy colour bins give both the same descriptor; the
  // hue-saturation-value histogram puts them in bins 15 (hue 0) and 191 (hue 330..345 degrees).
  const cv::Mat red(64, 64, CV_8UC3, cv::Scalar(20, 20, 200));
  const cv::Mat redder(64, 64, CV_8UC3, cv::Scalar(60, 20, 160));
  ASSERT_EQ(ExtractCedd(red, DescriptorVariant::kCeddRobust).values,
            ExtractCedd(redder, DescriptorVariant::kCeddRobust).values);
  const Descriptor a = ExtractCedd(red, DescriptorVariant::kCeddHsvHog);
  const Descriptor b = ExtractCedd(redder, DescriptorVariant::kCeddHsvHog);
  EXPECT_EQ(a.variant, DescriptorVariant::kCeddHsvHog);
  EXPECT_EQ(a.values[kColourChannelOffset + 15], 7);
  EXPECT_EQ(b.values[kColourChannelOffset + 191], 7);
  EXPECT_LT(Tanimoto(a.values, b.values), 0.9);
  // cedd-hsv-hog starts with cedd-robust's CEDD, unchanged.
  EXPECT_TRUE(std::equal(a.values.begin(), a.values.begin() + kCeddSize,
                         ExtractCedd(red, DescriptorVariant::kCeddRobust).values.begin()));
}

TEST(AppearanceChannelsTest, AFaintTintCountsAsEveryHue) {
  // A bluish white, BGR (204, 200, 200): the canonical frame scales it by 200 / 204 to
  // (200, 196, 196); OpenCV's HSV gives hue 120 (bin 8), saturation 5, value 200 (bin 3).
  // Its chroma, 5 * 200 / 255 = 3.9, is a quarter of kSureChroma: a quarter of its count is
  // blue's, the rest is spread over the 12 hues of (saturation 0, value 3), bins h * 16 + 3.
  // Each then holds at least 48 * sqrt(0.75 / 12) = 12, clipped to 7; a hue taken at its
  // word would fill bin 131 alone.
  const DescriptorValues tint = Channels(cv::Mat(64, 64, CV_8UC3, cv::Scalar(204, 200, 200)));
  for (int i = 0; i < kColourChannelSize; ++i) {
    EXPECT_EQ(tint[kColourChannelOffset + i], i % 16 == 3 ? 7 : 0) << "colour bin " << i;
  }
  // Chroma 48 (BGR 248, 200, 200 -> 200, 161, 161): above kSureChroma, blue's alone.
  const DescriptorValues blue = Channels(cv::Mat(64, 64, CV_8UC3, cv::Scalar(248, 200, 200)));
  EXPECT_EQ(blue[kColourChannelOffset + 131], 7);
  EXPECT_EQ(Sum(blue, kColourChannelOffset, kColourChannelSize), 7);
}

TEST(AppearanceChannelsTest, SoftHueEdgesKeepAHueThatMovesAcrossAnEdgeInBothBins) {
  // Orange, BGR (0, G, 200), unchanged by the canonical frame (its brightest channel is already
  // 200): OpenCV's hue is 14 for G = 93, 15 for G = 100, 16 for G = 107 (30 degrees, and 2
  // degrees either side: what compression or noise does to a hue), saturation 255, value 200.
  // A hue bin is 15 units wide and hue 15 is
  // the edge between hue bins 0 and 1: bins (0 * 4 + 3) * 4 + 3 = 15 and (1 * 4 + 3) * 4 + 3 = 31.
  const auto orange = [](int green) { return cv::Mat(64, 64, CV_8UC3, cv::Scalar(0, green, 200)); };
  const DescriptorVariant soft = DescriptorVariant::kCeddSoftHsvHog;
  // On the edge: half in each bin, both clipped to 7 (norm 40 over two equal bins: 28).
  const DescriptorValues edge = Channels(orange(100), soft);
  for (int i = 0; i < kColourChannelSize; ++i) {
    EXPECT_EQ(edge[kColourChannelOffset + i], i == 15 || i == 31 ? 7 : 0) << "colour bin " << i;
  }
  // Hues 14 and 16 lie 1/15 of a bin from the edge (inside the reach of a quarter): each gives
  // the bin beyond 0.5 * (1 - (1/15) / 0.25) = 0.37 of its count, so both hold both bins, at
  // 40 * sqrt(0.37) = 24 and 40 * sqrt(0.63) = 32, each clipped to 7: the colours are the same.
  const DescriptorValues below = Channels(orange(93), soft);
  const DescriptorValues above = Channels(orange(107), soft);
  EXPECT_EQ(below[kColourChannelOffset + 15], 7);
  EXPECT_EQ(below[kColourChannelOffset + 31], 7);
  EXPECT_EQ(Tanimoto(ColourChannelOnly(below), ColourChannelOnly(above)), 1.0);
  // cedd-hsv-hog's hard edges put the two shades in different bins: nothing in common.
  const DescriptorValues hard_below = Channels(orange(93));
  const DescriptorValues hard_above = Channels(orange(107));
  EXPECT_EQ(hard_below[kColourChannelOffset + 15], 7);
  EXPECT_EQ(hard_above[kColourChannelOffset + 31], 7);
  EXPECT_EQ(Tanimoto(ColourChannelOnly(hard_below), ColourChannelOnly(hard_above)), 0.0);
  // A hue in the middle half of its bin stays in it: hue 19 (BGR 0, 127, 200) is 4/15 of a bin
  // from the edge, beyond the reach.
  const DescriptorValues inside = Channels(orange(127), soft);
  EXPECT_EQ(inside[kColourChannelOffset + 31], 7);
  EXPECT_EQ(Sum(inside, kColourChannelOffset, kColourChannelSize), 7);
}

TEST(AppearanceChannelsTest, SoftHueEdgesLeaveCeddAndTheGradientCellsAsTheyWere) {
  // A red square on grey: cedd-soft-hsv-hog's CEDD is cedd-robust's and its gradient cells are
  // cedd-hsv-hog's; only the colour histogram differs in definition.
  cv::Mat image(128, 128, CV_8UC3, cv::Scalar(120, 120, 120));
  cv::rectangle(image, cv::Rect(32, 32, 64, 64), cv::Scalar(30, 40, 210), cv::FILLED);
  const Descriptor soft = ExtractCedd(image, DescriptorVariant::kCeddSoftHsvHog);
  const Descriptor hard = ExtractCedd(image, DescriptorVariant::kCeddHsvHog);
  EXPECT_EQ(soft.variant, DescriptorVariant::kCeddSoftHsvHog);
  EXPECT_TRUE(std::equal(soft.values.begin(), soft.values.begin() + kCeddSize,
                         ExtractCedd(image, DescriptorVariant::kCeddRobust).values.begin()));
  EXPECT_TRUE(std::equal(soft.values.begin() + kGradientChannelOffset, soft.values.end(),
                         hard.values.begin() + kGradientChannelOffset));
}

TEST(AppearanceChannelsTest, SensorNoiseDoesNotMoveAGreysColours) {
  // A grey card on a darker grey wall, then the same under sensor noise of deviation 25 grey
  // levels (what a dim room's camera adds). Noise turns a grey pixel's hue random; were that
  // hue counted, every noisy frame of a grey object would match some coloured one.
  cv::Mat clean(128, 128, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::rectangle(clean, cv::Rect(40, 40, 48, 48), cv::Scalar(170, 170, 170), cv::FILLED);
  cv::Mat noise(clean.size(), CV_16SC3);
  cv::RNG random(7);
  random.fill(noise, cv::RNG::NORMAL, 0, 25);
  cv::Mat noisy;
  clean.convertTo(noisy, CV_16SC3);
  noisy += noise;
  noisy.convertTo(noisy, CV_8UC3);
  EXPECT_GE(Tanimoto(ColourChannelOnly(Channels(clean)), ColourChannelOnly(Channels(noisy))), 0.9);
}

// eth-80-dev's ring views, each cropped to its box grown by 10% a side.
struct RealView {
  std::string object;
  double azimuth = 0;
  cv::Mat region;
};

std::vector<RealView> Eth80RingViews() {
  const auto folder = testing::DataDir() / "eth-80-dev";
  std::map<std::string, cv::Rect> boxes;
  std::ifstream box_file(folder / "boxes.csv");
  std::string line;
  std::getline(box_file, line);  // header
  while (std::getline(box_file, line)) {
    std::istringstream fields(line);
    std::string path, x, y, w, h;
    std::getline(fields, path, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, w, ',');
    std::getline(fields, h, ',');
    boxes[path] = cv::Rect(std::stoi(x), std::stoi(y), std::stoi(w), std::stoi(h));
  }
  std::vector<RealView> views;
  std::ifstream ring(folder / "ring.csv");
  std::getline(ring, line);
  while (std::getline(ring, line)) {
    std::istringstream fields(line);
    std::string path, object, azimuth;
    std::getline(fields, path, ',');
    std::getline(fields, object, ',');
    std::getline(fields, azimuth, ',');
    const cv::Mat image = ReadImageFile((folder / path).string());
    const cv::Rect box = boxes.at(path);
    const int dx = static_cast<int>(std::lround(0.1 * box.width));
    const int dy = static_cast<int>(std::lround(0.1 * box.height));
    const cv::Rect grown =
        cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) &
        cv::Rect(0, 0, image.cols, image.rows);
    views.push_back({object, std::stod(azimuth), image(grown).clone()});
  }
  return views;
}

// Share of views whose most similar other view (the query's own left out) shows the same object.
double NearestViewHitRate(const std::vector<RealView>& views, DescriptorVariant variant) {
  std::vector<DescriptorValues> described;
  for (const RealView& view : views) described.push_back(ExtractCedd(view.region, variant).values);
  int hits = 0;
  for (std::size_t q = 0; q < views.size(); ++q) {
    double best = -1;
    std::size_t nearest = 0;
    for (std::size_t c = 0; c < views.size(); ++c) {
      if (c == q) continue;
      const double similarity = Tanimoto(described[q], described[c]);
      if (similarity > best) best = similarity, nearest = c;
    }
    hits += views[nearest].object == views[q].object ? 1 : 0;
  }
  return 100.0 * hits / static_cast<double>(views.size());
}

TEST(AppearanceChannelsTest, TellsRealLookAlikeObjectsApartWhereCeddCannot) {
  const std::vector<RealView> views = Eth80RingViews();
  ASSERT_EQ(views.size(), 640u);  // 40 objects x 16 azimuths
  const double cedd = NearestViewHitRate(views, DescriptorVariant::kCeddRobust);
  const double appearance = NearestViewHitRate(views, DescriptorVariant::kCeddHsvHog);
  // docs/results/real-objects.md has these figures and the protocol's. The appearance channels
  // must at least halve CEDD's misses.
  EXPECT_GE(appearance, 93.0) << "cedd-hsv-hog " << appearance << "%";
  EXPECT_LT(2 * (100 - appearance), 100 - cedd)
      << "cedd-robust " << cedd << "%, cedd-hsv-hog " << appearance << "%";
}

// COIL-100's 100 objects, each described at every 20 degrees; queries 10 degrees from those
// views (at 10 and 190), each compressed at JPEG quality 10 and noisy at variance 0.03 (a
// deviation of 44 grey levels): the share whose most similar view shows the same object.
struct CoilHitRates {
  double jpeg = 0;
  double noise = 0;
};
CoilHitRates CoilNearestViewHitRates(DescriptorVariant variant) {
  std::vector<std::pair<int, DescriptorValues>> views;
  const auto file = [](int object, int azimuth) {
    return testing::CoilDir() + "/obj" + std::to_string(object) + "__" + std::to_string(azimuth) +
           ".png";
  };
  for (int object = 1; object <= 100; ++object) {
    for (int azimuth = 0; azimuth < 360; azimuth += 20) {
      views.emplace_back(object, ExtractCedd(ReadImageFile(file(object, azimuth)), variant).values);
    }
  }
  const auto nearest = [&views](const DescriptorValues& query) {
    double best = -1;
    int object = 0;
    for (const auto& [candidate, values] : views) {
      const double similarity = Tanimoto(query, values);
      if (similarity > best) best = similarity, object = candidate;
    }
    return object;
  };
  int jpeg_hits = 0, noise_hits = 0, queries = 0;
  for (int object = 1; object <= 100; ++object) {
    for (const int azimuth : {10, 190}) {
      const cv::Mat image = ReadImageFile(file(object, azimuth));
      std::vector<std::uint8_t> encoded;
      cv::imencode(".jpg", image, encoded, {cv::IMWRITE_JPEG_QUALITY, 10});
      const cv::Mat compressed = cv::imdecode(encoded, cv::IMREAD_COLOR);
      const cv::Mat noisy = AddGaussianNoise(image, 0.03, 100 * object + azimuth);
      jpeg_hits += nearest(ExtractCedd(compressed, variant).values) == object ? 1 : 0;
      noise_hits += nearest(ExtractCedd(noisy, variant).values) == object ? 1 : 0;
      ++queries;
    }
  }
  return {100.0 * jpeg_hits / queries, 100.0 * noise_hits / queries};
}

TEST(AppearanceChannelsTest, SoftHueEdgesKeepCoilObjectsUnderStrongCompressionAndNoise) {
  const CoilHitRates hard = CoilNearestViewHitRates(DescriptorVariant::kCeddHsvHog);
  const CoilHitRates soft = CoilNearestViewHitRates(DescriptorVariant::kCeddSoftHsvHog);
  // docs/results/real-objects.md, "Soft hue edges": hard edges took objects whose colour lies
  // near a hue edge for their neighbour of the next hue under both. Measured: 87.5 and 86.0
  // against 93.5 and 94.0; asked, at least 8 queries of 200 more found under each.
  EXPECT_GE(soft.jpeg, hard.jpeg + 4)
      << "JPEG 10: hard edges " << hard.jpeg << "%, soft " << soft.jpeg << "%";
  EXPECT_GE(soft.noise, hard.noise + 4)
      << "noise 0.03: hard edges " << hard.noise << "%, soft " << soft.noise << "%";
}

TEST(AppearanceChannelsTest, TheColourLayoutTellsMoreLookAlikesApart) {
  const std::vector<RealView> views = Eth80RingViews();
  const double hog = NearestViewHitRate(views, DescriptorVariant::kCeddHsvHog);
  const double layout = NearestViewHitRate(views, DescriptorVariant::kCeddHsvLayout);
  // docs/results/real-objects.md, "The colour layout": 32 views of 640 missed against 39 (1.1
  // points); under the protocol's distortions and among look-alikes the gap is wider.
  EXPECT_GE(layout, hog + 0.75) << "cedd-hsv-hog " << hog << "%, cedd-hsv-layout " << layout << "%";
}

}  // namespace
}  // namespace orbit
