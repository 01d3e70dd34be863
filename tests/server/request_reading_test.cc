// Requests read into core values (server/request_reading.h): what a frame or a view becomes,
// and every refusal as INVALID_ARGUMENT naming the field.
#include "server/request_reading.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "client/image_file.h"
#include "core/cedd.h"
#include "core/view_description.h"
#include "tests/support/test_data.h"

namespace orbit::server {
namespace {

constexpr auto kLire = DescriptorVariant::kCeddLire;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

cv::Mat CoilImage() {
  return ReadImageFile((orbit::testing::DataDir() / "coil-100" / "obj9__30.png").string());
}

std::string Png(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".png", image, bytes);
  return std::string(bytes.begin(), bytes.end());
}

std::string Cedd(std::uint8_t fill) { return std::string(kDescriptorSize, static_cast<char>(fill)); }

void ExpectInvalid(const grpc::Status& status, const std::string& message) {
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << message;
  EXPECT_EQ(status.error_message(), message);
}

TEST(RequestReadingTest, FrameWithCeddOrImage) {
  v1::Frame frame;
  frame.set_cedd(Cedd(3));
  frame.set_azimuth_deg(-725.5);  // any finite value
  QueryFrame query;
  ASSERT_TRUE(ToQueryFrame(frame, kLire, &query).ok());
  EXPECT_EQ(query.azimuth, -725.5);
  EXPECT_EQ(query.descriptor.values[100], 3);
  EXPECT_EQ(query.descriptor.variant, kLire);

  // An image is described on the server, its region alone when given.
  const cv::Mat image = CoilImage();
  frame.clear_cedd();
  frame.set_image(Png(image));
  frame.mutable_region()->set_x(10);
  frame.mutable_region()->set_y(20);
  frame.mutable_region()->set_width(60);
  frame.mutable_region()->set_height(50);
  ASSERT_TRUE(ToQueryFrame(frame, DescriptorVariant::kCeddFull, &query).ok());
  EXPECT_EQ(query.descriptor.values,
            ExtractCedd(image(cv::Rect(10, 20, 60, 50)), DescriptorVariant::kCeddFull).values);
}

TEST(RequestReadingTest, BadFramesAreRefusedNamingTheField) {
  QueryFrame query;
  v1::Frame frame;
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "a frame needs exactly one of cedd and image");
  frame.set_cedd(Cedd(1));
  frame.set_image("x");
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "a frame needs exactly one of cedd and image");
  frame.clear_image();
  frame.set_cedd(Cedd(8));
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "frame.cedd value 8 at index 0 is outside 0..7");
  frame.set_cedd("abc");
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "frame.cedd has 3 values, expected 144");
  frame.set_cedd(Cedd(1));
  frame.set_azimuth_deg(kNaN);
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "frame.azimuth_deg must be a finite number");
  frame.set_azimuth_deg(0);
  frame.set_elevation_deg(INFINITY);
  ExpectInvalid(ToQueryFrame(frame, kLire, &query), "frame.elevation_deg must be a finite number");
  frame.clear_elevation_deg();
  frame.clear_cedd();
  frame.set_image("not an image");
  ExpectInvalid(ToQueryFrame(frame, kLire, &query),
                "image is not a PNG, JPEG or other image OpenCV can decode");
  frame.set_image(Png(CoilImage()));
  frame.mutable_region()->set_x(100);
  frame.mutable_region()->set_width(40);
  frame.mutable_region()->set_height(10);
  ExpectInvalid(ToQueryFrame(frame, kLire, &query),
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
  ASSERT_TRUE(ToModelView(view, kLire, &stored, &thumbnail).ok());
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
  ASSERT_TRUE(ToModelView(view, kLire, &stored, &thumbnail).ok());
  EXPECT_EQ(stored.typical_distance, 0);  // unknown
  view.set_typical_distance(0.3);
  ASSERT_TRUE(ToModelView(view, kLire, &stored, &thumbnail).ok());
  EXPECT_EQ(stored.typical_distance, 0.3);
  view.set_typical_distance(1.5);
  ExpectInvalid(ToModelView(view, kLire, &stored, &thumbnail),
                "view.typical_distance must be in [0, 1]");
  view.set_typical_distance(0.3);
  view.set_thumbnail(std::string(64 * 1024 + 1, 'x'));
  ExpectInvalid(ToModelView(view, kLire, &stored, &thumbnail),
                "view.thumbnail is 65537 bytes; at most 65536");
  view.clear_thumbnail();
  view.set_cedd(Cedd(9));
  ExpectInvalid(ToModelView(view, kLire, &stored, &thumbnail),
                "view.cedd value 9 at index 0 is outside 0..7");
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
