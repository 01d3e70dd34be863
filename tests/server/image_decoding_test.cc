// An uploaded image decoded as the server decodes it (server/image_decoding.h): the header's
// size, 8-bit samples, refusals before decoding and of corrupt data, each naming the field.
#include "server/image_decoding.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace orbit::server {
namespace {

constexpr std::int64_t kMaxPixels = 4096 * 4096;

std::string Encode(const std::string& extension, const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes)) << extension;
  return std::string(bytes.begin(), bytes.end());
}

// Each decoded image holds one of the process's decode slots (one per core) until it is
// destroyed, so each lives in a scope of its own here.
TEST(ImageDecodingTest, PngAndJpegDecodeToTheirSizeInEightBitSamples) {
  {
    cv::Mat colour(30, 50, CV_8UC3);
    cv::randu(colour, 0, 256);
    DecodedImage png;
    ASSERT_TRUE(DecodeImage(Encode(".png", colour), "frame.image", kMaxPixels, &png).ok());
    EXPECT_EQ(png.pixels.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(png.pixels, colour, cv::NORM_INF), 0);  // lossless
  }
  {
    DecodedImage jpeg;
    const cv::Mat grey(7, 3, CV_8UC1, cv::Scalar(90));
    ASSERT_TRUE(DecodeImage(Encode(".jpg", grey), "frame.image", kMaxPixels, &jpeg).ok());
    EXPECT_EQ(jpeg.pixels.type(), CV_8UC1);
    EXPECT_EQ(jpeg.pixels.size(), cv::Size(3, 7));
  }
  {
    // 16-bit samples are scaled down by 256: 0x1234 -> 0x12.
    const cv::Mat deep(4, 6, CV_16UC4, cv::Scalar(0x1234, 0x8000, 0xffff, 0x00ff));
    DecodedImage scaled;
    ASSERT_TRUE(DecodeImage(Encode(".png", deep), "view.image", kMaxPixels, &scaled).ok());
    EXPECT_EQ(scaled.pixels.type(), CV_8UC4);
    EXPECT_EQ(scaled.pixels.at<cv::Vec4b>(3, 5), cv::Vec4b(0x12, 0x80, 0xff, 0x01));
  }
}

TEST(ImageDecodingTest, RefusalsNameTheField) {
  const std::string png = Encode(".png", cv::Mat(20, 10, CV_8UC3, cv::Scalar(1, 2, 3)));
  DecodedImage image;
  grpc::Status s = DecodeImage(png, "view.image", 199, &image);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(s.error_message(), "view.image is 10x20 pixels; at most 199 pixels are decoded");
  EXPECT_TRUE(image.pixels.empty());

  s = DecodeImage("GIF89a", "frame.image", kMaxPixels, &image);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(s.error_message(),
            "frame.image is not a PNG or JPEG image (the formats Orbit decodes)");

  s = DecodeImage(png.substr(0, 60), "frame.image", kMaxPixels, &image);  // header, no data
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(s.error_message(),
            "frame.image cannot be decoded: its PNG data is corrupt or truncated");
}

}  // namespace
}  // namespace orbit::server
