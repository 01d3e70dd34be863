// Requests read into core values (server/request_reading.h): what a frame or a view becomes,
// and every refusal naming the field: INVALID_ARGUMENT, or RESOURCE_EXHAUSTED for an image above
// the server's pixel limit.
#include "server/request_reading.h"

#include <zlib.h>

#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "client/image_file.h"
#include "core/descriptor/blur_estimate.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/noise_estimate.h"
#include "core/descriptor/view_description.h"
#include "server/decode_slots.h"
#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

constexpr auto kLire = DescriptorVariant::kCeddLire;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const ServerLimits kLimits;  // the defaults: images up to 4096x4096

cv::Mat CoilImage() {
  return ReadImageFile((orbit::testing::DataDir() / "coil-100" / "obj9__30.png").string());
}

std::string Png(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".png", image, bytes);
  return std::string(bytes.begin(), bytes.end());
}

std::string Jpeg(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", image, bytes);
  return std::string(bytes.begin(), bytes.end());
}

// A decompression bomb: a real PNG of width x 1 black pixels (a few hundred bytes) whose header
// (IHDR, with its CRC fixed) claims `height` rows.
std::string PngBomb(int width, std::uint32_t height) {
  std::string png = Png(cv::Mat::zeros(1, width, CV_8UC3));
  for (int i = 0; i < 4; ++i) png[20 + i] = static_cast<char>(height >> (24 - 8 * i));
  const auto crc = crc32(0, reinterpret_cast<const Bytef*>(png.data() + 12), 4 + 13);
  for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  return png;
}

std::string Cedd(std::uint8_t fill) { return std::string(kCeddSize, static_cast<char>(fill)); }

void ExpectInvalid(const grpc::Status& status, const std::string& message) {
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << message;
  EXPECT_EQ(status.error_message(), message);
}

TEST(RequestReadingTest, FrameWithCeddOrImage) {
  v1::Frame frame;
  frame.set_cedd(Cedd(3));
  frame.set_azimuth_deg(-725.5);  // any finite value
  QueryFrame query;
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_EQ(query.azimuth, -725.5);
  EXPECT_EQ(query.descriptor.values[100], 3);
  EXPECT_EQ(query.descriptor.variant, kLire);
  // A device without an orientation sensor leaves the azimuth unset; 0 set explicitly is a
  // reading like any other.
  frame.set_azimuth_deg(0);
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_EQ(query.azimuth, 0.0);
  frame.clear_azimuth_deg();
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_FALSE(query.azimuth.has_value());
  frame.set_azimuth_deg(-725.5);

  // An image is described on the server, its region alone when given.
  const cv::Mat image = CoilImage();
  frame.clear_cedd();
  frame.set_image(Png(image));
  frame.mutable_region()->set_x(10);
  frame.mutable_region()->set_y(20);
  frame.mutable_region()->set_width(60);
  frame.mutable_region()->set_height(50);
  ASSERT_TRUE(ToQueryFrame(frame, DescriptorVariant::kCeddFull, kLimits, &query).ok());
  EXPECT_EQ(query.descriptor.values,
            ExtractCedd(image(cv::Rect(10, 20, 60, 50)), DescriptorVariant::kCeddFull).values);
  // ... and its noise and blur measured there, for the calibrated rule's allowance.
  ASSERT_TRUE(query.noise_sigma.has_value());
  EXPECT_EQ(*query.noise_sigma, EstimateNoiseSigma(image(cv::Rect(10, 20, 60, 50))));
  ASSERT_TRUE(query.blur.has_value());
  EXPECT_EQ(*query.blur, EstimateBlur(image(cv::Rect(10, 20, 60, 50))));
}

TEST(RequestReadingTest, TheDevicesQualityReadingsReachTheEngine) {
  v1::Frame frame;
  frame.set_cedd(Cedd(3));
  QueryFrame query;
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_FALSE(query.noise_sigma.has_value());  // not measured: no allowance
  EXPECT_FALSE(query.blur.has_value());
  frame.mutable_quality()->set_noise_sigma(24.5);
  frame.mutable_quality()->set_sharpness(80);
  frame.mutable_quality()->set_blur(0.75);
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_EQ(query.noise_sigma, 24.5);
  EXPECT_EQ(query.blur, 0.75);
  // The device's readings win over the server's own measurement of an image.
  frame.clear_cedd();
  frame.set_image(Png(CoilImage()));
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_EQ(query.noise_sigma, 24.5);
  EXPECT_EQ(query.blur, 0.75);
  // A reading from the previous frame does not linger.
  frame.clear_quality();
  frame.clear_image();
  frame.set_cedd(Cedd(3));
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_FALSE(query.noise_sigma.has_value());
  EXPECT_FALSE(query.blur.has_value());
}

TEST(RequestReadingTest, BadFramesAreRefusedNamingTheField) {
  QueryFrame query;
  v1::Frame frame;
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "a frame needs exactly one of cedd and image");
  frame.set_cedd(Cedd(1));
  frame.set_image("x");
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "a frame needs exactly one of cedd and image");
  frame.clear_image();
  frame.set_cedd(Cedd(8));
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.cedd value 8 at index 0 is outside 0..7");
  frame.set_cedd("abc");
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.cedd has 3 values, expected 144");
  frame.set_cedd(Cedd(1));
  ExpectInvalid(ToQueryFrame(frame, DescriptorVariant::kCeddHsvHog, kLimits, &query),
                "frame.appearance has 0 values, expected 336 for cedd-hsv-hog");
  frame.set_appearance(std::string(336, '\2'));
  ASSERT_TRUE(ToQueryFrame(frame, DescriptorVariant::kCeddHsvHog, kLimits, &query).ok());
  EXPECT_EQ(query.descriptor.values[kDescriptorSize - 1], 2);
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.appearance has 336 values, expected 0 for cedd-lire");
  frame.clear_appearance();
  frame.set_cedd(Cedd(1));
  frame.set_azimuth_deg(kNaN);
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.azimuth_deg must be a finite number");
  frame.set_azimuth_deg(0);
  frame.set_elevation_deg(INFINITY);
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.elevation_deg must be a finite number");
  frame.clear_elevation_deg();
  for (const auto& [sigma, text] : {std::pair{-1.0, "-1"}, {255.5, "255.5"}, {kNaN, "nan"}}) {
    frame.mutable_quality()->set_noise_sigma(sigma);
    ExpectInvalid(
        ToQueryFrame(frame, kLire, kLimits, &query),
        std::string("frame.quality.noise_sigma must be in [0, 255] grey levels, got ") + text);
  }
  frame.mutable_quality()->set_noise_sigma(3);
  for (const auto& [blur, text] : {std::pair{-0.5, "-0.5"}, {1.5, "1.5"}, {kNaN, "nan"}}) {
    frame.mutable_quality()->set_blur(blur);
    ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                  std::string("frame.quality.blur must be in [0, 1], got ") + text);
  }
  frame.clear_quality();
  frame.clear_cedd();
  frame.set_image("not an image");
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.image is not a PNG or JPEG image (the formats Orbit decodes)");
  frame.set_image(Png(CoilImage()));
  frame.mutable_region()->set_x(100);
  frame.mutable_region()->set_width(40);
  frame.mutable_region()->set_height(10);
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "region must be non-empty and inside the 128x128 image");
}

TEST(RequestReadingTest, ViewFromAnImageIsDescribedAsEveryEnrollmentPathDoesIt) {
  const cv::Mat image = CoilImage();
  v1::View view;
  view.set_image(Png(image));
  view.set_azimuth_deg(30);
  view.set_elevation_deg(5);
  view.set_thumbnail("thumb");
  ModelView stored;
  std::string thumbnail;
  ASSERT_TRUE(ToModelView(view, kLire, kLimits, &stored, &thumbnail).ok());
  const ViewDescription expected = DescribeView(image, kLire);
  EXPECT_EQ(stored.descriptor, expected.descriptor);
  EXPECT_EQ(stored.typical_distance, expected.typical_distance);
  EXPECT_EQ(stored.azimuth, 30);
  EXPECT_EQ(stored.elevation, 5);
  EXPECT_EQ(thumbnail, "thumb");
}

TEST(RequestReadingTest, ViewWithCeddKeepsItsTypicalDistanceAndRefusesBadOnes) {
  v1::View view;
  view.set_cedd(Cedd(2));
  view.set_azimuth_deg(400);
  ModelView stored;
  std::string thumbnail;
  ASSERT_TRUE(ToModelView(view, kLire, kLimits, &stored, &thumbnail).ok());
  EXPECT_EQ(stored.typical_distance, 0);  // unknown
  view.set_typical_distance(0.3);
  ASSERT_TRUE(ToModelView(view, kLire, kLimits, &stored, &thumbnail).ok());
  EXPECT_EQ(stored.typical_distance, 0.3);
  view.set_typical_distance(1.5);
  ExpectInvalid(ToModelView(view, kLire, kLimits, &stored, &thumbnail),
                "view.typical_distance must be in [0, 1]");
  view.set_typical_distance(0.3);
  view.set_thumbnail(std::string(64 * 1024 + 1, 'x'));
  ExpectInvalid(ToModelView(view, kLire, kLimits, &stored, &thumbnail),
                "view.thumbnail is 65537 bytes; at most 65536");
  view.clear_thumbnail();
  view.set_cedd(Cedd(9));
  ExpectInvalid(ToModelView(view, kLire, kLimits, &stored, &thumbnail),
                "view.cedd value 9 at index 0 is outside 0..7");
}

TEST(RequestReadingTest, ImagesAboveTheServersPixelLimitAreRefusedBeforeDecoding) {
  // A decompression bomb: 20000x20000 pixels (1.2 GB decoded) in a few hundred bytes.
  v1::Frame frame;
  frame.set_image(PngBomb(20000, 20000));
  QueryFrame query;
  grpc::Status s = ToQueryFrame(frame, kLire, kLimits, &query);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(s.error_message(),
            "frame.image is 20000x20000 pixels; at most 16777216 pixels (4096x4096) are decoded");
  v1::View view;
  view.set_image(frame.image());
  ModelView stored;
  std::string thumbnail;
  s = ToModelView(view, kLire, kLimits, &stored, &thumbnail);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(s.error_message(),
            "view.image is 20000x20000 pixels; at most 16777216 pixels (4096x4096) are decoded");

  // The limit is the server's: a 128x128 image passes at 128 x 128 pixels, not one below.
  ServerLimits limits;
  limits.max_image_pixels = 128 * 128;
  frame.set_image(Png(CoilImage()));
  EXPECT_TRUE(ToQueryFrame(frame, kLire, limits, &query).ok());
  limits.max_image_pixels = 128 * 128 - 1;
  s = ToQueryFrame(frame, kLire, limits, &query);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(s.error_message(), "frame.image is 128x128 pixels; at most 16383 pixels are decoded");
  view.set_image(Jpeg(CoilImage()));
  s = ToModelView(view, kLire, limits, &stored, &thumbnail);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(s.error_message(), "view.image is 128x128 pixels; at most 16383 pixels are decoded");
}

TEST(RequestReadingTest, OnlyPngAndJpegImagesAreDecoded) {
  const cv::Mat image = CoilImage();
  v1::Frame frame;
  QueryFrame query;
  const std::string jpeg = Jpeg(image);
  frame.set_image(jpeg);
  ASSERT_TRUE(ToQueryFrame(frame, kLire, kLimits, &query).ok());
  EXPECT_EQ(query.descriptor.values,
            ExtractCedd(cv::imdecode(std::vector<std::uint8_t>(jpeg.begin(), jpeg.end()),
                                     cv::IMREAD_UNCHANGED),
                        kLire)
                .values);

  // OpenCV decodes BMP, but the server reads no BMP header, so it decodes none.
  std::vector<std::uint8_t> bmp;
  cv::imencode(".bmp", image, bmp);
  frame.set_image(std::string(bmp.begin(), bmp.end()));
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.image is not a PNG or JPEG image (the formats Orbit decodes)");
  // A sound header over broken data.
  frame.set_image(Png(image).substr(0, 100));
  ExpectInvalid(ToQueryFrame(frame, kLire, kLimits, &query),
                "frame.image cannot be decoded: its PNG data is corrupt or truncated");
  v1::View view;
  view.set_image(jpeg.substr(0, jpeg.find("\xff\xc4")));  // up to the frame header, no scan
  ModelView stored;
  std::string thumbnail;
  ExpectInvalid(ToModelView(view, kLire, kLimits, &stored, &thumbnail),
                "view.image cannot be decoded: its JPEG data is corrupt or truncated");
}

TEST(RequestReadingTest, ImageDecodesWaitForAFreeDecodeSlotAndRefusalsDoNot) {
  std::future<grpc::Status> decoding;  // declared first: joined after the slots are given back
  v1::Frame frame;
  frame.set_image(Png(CoilImage()));
  QueryFrame query;
  {
    std::vector<DecodeSlots::Slot> every_slot;
    for (int i = 0; i < ProcessDecodeSlots().capacity(); ++i) {
      every_slot.push_back(ProcessDecodeSlots().Acquire());
    }
    decoding = std::async(std::launch::async,
                          [&frame, &query] { return ToQueryFrame(frame, kLire, kLimits, &query); });
    // Every slot is taken, so the image waits, however long it is given.
    EXPECT_EQ(decoding.wait_for(std::chrono::milliseconds(200)), std::future_status::timeout);
    // Meanwhile a bomb is refused from its header and a descriptor needs no slot.
    v1::Frame other;
    QueryFrame other_query;
    other.set_image(PngBomb(20000, 20000));
    EXPECT_EQ(ToQueryFrame(other, kLire, kLimits, &other_query).error_code(),
              grpc::StatusCode::RESOURCE_EXHAUSTED);
    other.set_cedd(Cedd(2));
    other.clear_image();
    EXPECT_TRUE(ToQueryFrame(other, kLire, kLimits, &other_query).ok());
  }
  const grpc::Status s = decoding.get();
  EXPECT_TRUE(s.ok()) << s.error_message();
  EXPECT_EQ(query.descriptor.values, ExtractCedd(CoilImage(), kLire).values);
}

TEST(RequestReadingTest, CheckVariantAcceptsUnsetOrTheServersOwn) {
  EXPECT_TRUE(CheckVariant(v1::DESCRIPTOR_VARIANT_UNSPECIFIED, kLire, "header.variant").ok());
  EXPECT_TRUE(CheckVariant(v1::CEDD_LIRE, kLire, "header.variant").ok());
  ExpectInvalid(CheckVariant(static_cast<v1::DescriptorVariant>(7), kLire, "header.variant"),
                "header.variant is unknown (7) but this server's models are cedd-lire; variants "
                "cannot be mixed");
}

}  // namespace
}  // namespace orbit::server
