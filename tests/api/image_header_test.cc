// The image budget (api/image_header.h): image sizes read from PNG and JPEG headers as the
// decoders read them, and the pixel limit with its message.
#include "api/image_header.h"

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace orbit {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr std::int64_t kDefaultMax = kDefaultMaxImagePixels;

std::string Encode(const std::string& extension, const cv::Mat& image,
                   const std::vector<int>& parameters = {}) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes, parameters)) << extension;
  return std::string(bytes.begin(), bytes.end());
}

// A noisy image, so that encoders keep every row.
cv::Mat Noise(int width, int height, int type) {
  cv::Mat image(height, width, type);
  cv::randu(image, 0, 255);
  return image;
}

std::string BigEndian32(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16),
          static_cast<char>(value >> 8), static_cast<char>(value)};
}

// A PNG chunk: length, type, data, CRC of type and data.
std::string PngChunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  const auto crc =
      crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()));
  return BigEndian32(static_cast<std::uint32_t>(data.size())) + body +
         BigEndian32(static_cast<std::uint32_t>(crc));
}

std::string Ihdr(std::uint32_t width, std::uint32_t height, int depth = 8, int colour = 2,
                 int interlace = 0) {
  return PngChunk("IHDR", BigEndian32(width) + BigEndian32(height) +
                              std::string{static_cast<char>(depth), static_cast<char>(colour), 0, 0,
                                          static_cast<char>(interlace)});
}

const std::string kPngSignature = "\x89PNG\r\n\x1a\n";

// A hand-made PNG header claiming width x height, with correct CRCs and no image data.
std::string PngClaiming(std::uint32_t width, std::uint32_t height, int depth = 8, int colour = 2,
                        int interlace = 0) {
  return kPngSignature + Ihdr(width, height, depth, colour, interlace) + PngChunk("IEND", "");
}

// A marker segment: 0xFF, the code, the length (which counts itself), the data.
std::string JpegSegment(std::uint8_t code, const std::string& data) {
  const auto length = static_cast<std::uint32_t>(data.size() + 2);
  return std::string{'\xff', static_cast<char>(code), static_cast<char>(length >> 8),
                     static_cast<char>(length)} +
         data;
}

std::string Sof(std::uint8_t code, std::uint32_t width, std::uint32_t height, int components = 3,
                int precision = 8) {
  std::string data{static_cast<char>(precision), static_cast<char>(height >> 8),
                   static_cast<char>(height),    static_cast<char>(width >> 8),
                   static_cast<char>(width),     static_cast<char>(components)};
  for (int c = 1; c <= components; ++c) data += std::string{static_cast<char>(c), 0x11, 0};
  return JpegSegment(code, data);
}

const std::string kSoi = "\xff\xd8";
const std::string kEoi = "\xff\xd9";
const std::string kApp0 = JpegSegment(0xe0, std::string("JFIF\0\1\1\0\0\1\0\1\0\0", 14));

// A hand-made JPEG header claiming width x height: SOI, APP0, the frame header, EOI.
std::string JpegClaiming(std::uint32_t width, std::uint32_t height, std::uint8_t sof = 0xc0) {
  return kSoi + kApp0 + Sof(sof, width, height) + kEoi;
}

ImageHeader Read(const std::string& bytes) {
  ImageHeader header;
  const grpc::Status s = ReadImageHeader(bytes, "frame.image", &header);
  EXPECT_TRUE(s.ok()) << s.error_message();
  return header;
}

grpc::Status ReadStatus(const std::string& bytes) {
  ImageHeader header;
  return ReadImageHeader(bytes, "frame.image", &header);
}

void ExpectInvalid(const std::string& bytes, const std::string& message) {
  const grpc::Status s = ReadStatus(bytes);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << message;
  EXPECT_EQ(s.error_message(), message);
}

// The header's size, checked against what OpenCV decodes from the same bytes.
void ExpectSizeAsDecoded(const std::string& bytes, ImageFormat format, int width, int height) {
  const ImageHeader header = Read(bytes);
  EXPECT_EQ(header.format, format);
  EXPECT_EQ(header.width, static_cast<std::uint32_t>(width));
  EXPECT_EQ(header.height, static_cast<std::uint32_t>(height));
  const cv::Mat decoded =
      cv::imdecode(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(decoded.cols, width);
  EXPECT_EQ(decoded.rows, height);
}

TEST(ImageHeaderTest, ReadsTheSizeOfRealPngImages) {
  ExpectSizeAsDecoded(Encode(".png", Noise(37, 21, CV_8UC3)), ImageFormat::kPng, 37, 21);
  ExpectSizeAsDecoded(Encode(".png", Noise(5, 300, CV_8UC1)), ImageFormat::kPng, 5, 300);
  ExpectSizeAsDecoded(Encode(".png", Noise(64, 48, CV_8UC4)), ImageFormat::kPng, 64, 48);
  ExpectSizeAsDecoded(Encode(".png", Noise(19, 7, CV_16UC1)), ImageFormat::kPng, 19, 7);
  ExpectSizeAsDecoded(Encode(".png", Noise(1, 1, CV_8UC3)), ImageFormat::kPng, 1, 1);
  ExpectSizeAsDecoded(Encode(".png", Noise(40, 30, CV_8UC1), {cv::IMWRITE_PNG_BILEVEL, 1}),
                      ImageFormat::kPng, 40, 30);
}

TEST(ImageHeaderTest, ReadsTheSizeOfRealJpegImages) {
  ExpectSizeAsDecoded(Encode(".jpg", Noise(640, 480, CV_8UC3)), ImageFormat::kJpeg, 640, 480);
  ExpectSizeAsDecoded(Encode(".jpg", Noise(33, 17, CV_8UC1)), ImageFormat::kJpeg, 33, 17);
  ExpectSizeAsDecoded(Encode(".jpg", Noise(300, 200, CV_8UC3), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}),
                      ImageFormat::kJpeg, 300, 200);
}

TEST(ImageHeaderTest, JpegSegmentsAreSkippedByTheirLengthAsLibjpegDoes) {
  const std::string image = Encode(".jpg", Noise(120, 90, CV_8UC3));
  const std::string rest = image.substr(2);  // after SOI
  // An EXIF-like APP1 carrying a whole 8x8 thumbnail, SOF included: the image is 120x90.
  const std::string thumbnail = Encode(".jpg", Noise(8, 8, CV_8UC3));
  const std::string with_thumbnail =
      kSoi + JpegSegment(0xe1, std::string("Exif\0\0", 6) + thumbnail) + rest;
  ExpectSizeAsDecoded(with_thumbnail, ImageFormat::kJpeg, 120, 90);
  // A comment holding bytes that look like a frame header.
  ExpectSizeAsDecoded(kSoi + JpegSegment(0xfe, Sof(0xc0, 9999, 9999)) + rest, ImageFormat::kJpeg,
                      120, 90);
  // Stray bytes and 0xFF fill bytes between segments, which libjpeg skips with a warning.
  ExpectSizeAsDecoded(
      kSoi + kApp0 + std::string("junk\xff\x00more", 10) + "\xff\xff\xff" + rest.substr(1),
      ImageFormat::kJpeg, 120, 90);
}

TEST(ImageHeaderTest, RefusesImagesAboveTheBudgetNamingTheirSizeAndTheMaximum) {
  // A decompression bomb: a PNG claiming 20000x20000 (1.2 GB decoded).
  const grpc::Status bomb =
      CheckImageBudget(Read(PngClaiming(20000, 20000)), kDefaultMax, "frame.image");
  EXPECT_EQ(bomb.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(bomb.error_message(),
            "frame.image is 20000x20000 pixels; at most 16777216 pixels (4096x4096) are decoded");
  const grpc::Status jpeg =
      CheckImageBudget(Read(JpegClaiming(65535, 65535, 0xc2)), kDefaultMax, "view.image");
  EXPECT_EQ(jpeg.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(jpeg.error_message(),
            "view.image is 65535x65535 pixels; at most 16777216 pixels (4096x4096) are decoded");

  // The default passes a 12 MP phone photo, a 4K frame, and exactly 4096x4096.
  EXPECT_EQ(kDefaultMax, 4096 * 4096);
  EXPECT_TRUE(CheckImageBudget(Read(JpegClaiming(4032, 3024)), kDefaultMax, "frame.image").ok());
  EXPECT_TRUE(CheckImageBudget(Read(JpegClaiming(3840, 2160)), kDefaultMax, "frame.image").ok());
  EXPECT_TRUE(CheckImageBudget(Read(PngClaiming(4096, 4096)), kDefaultMax, "frame.image").ok());
  EXPECT_FALSE(CheckImageBudget(Read(PngClaiming(4097, 4096)), kDefaultMax, "frame.image").ok());
  EXPECT_TRUE(CheckImageBudget(Read(PngClaiming(16777216, 1)), kDefaultMax, "frame.image").ok());

  // Another maximum: its side is shown only when it is a square.
  EXPECT_EQ(CheckImageBudget(Read(PngClaiming(1001, 1000)), 1000000, "frame.image").error_message(),
            "frame.image is 1001x1000 pixels; at most 1000000 pixels (1000x1000) are decoded");
  EXPECT_EQ(
      CheckImageBudget(Read(PngClaiming(4000, 3001)), 12000000, "frame.image").error_message(),
      "frame.image is 4000x3001 pixels; at most 12000000 pixels are decoded");
}

TEST(ImageHeaderTest, SizesWhoseProductOverflowsAreRefusedNotWrapped) {
  // 65536 x 65536 = 2^32, 0 in 32 bits; 2^31-1 squared is near 2^62.
  for (const auto& [width, height] : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {65536, 65536}, {0x7fffffff, 0x7fffffff}, {0x7fffffff, 2}, {4294967, 1001}}) {
    const grpc::Status s =
        CheckImageBudget(Read(PngClaiming(width, height)), kDefaultMax, "frame.image");
    EXPECT_EQ(s.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << width << "x" << height;
    EXPECT_THAT(s.error_message(), StartsWith("frame.image is " + std::to_string(width) + "x" +
                                              std::to_string(height) + " pixels"));
  }
  // Above the PNG format's 31 bits: malformed, as libpng says.
  ExpectInvalid(PngClaiming(0x80000000u, 1),
                "frame.image is a PNG whose header gives a width or height above 2^31 - 1");
  ExpectInvalid(PngClaiming(1, 0xffffffffu),
                "frame.image is a PNG whose header gives a width or height above 2^31 - 1");
}

TEST(ImageHeaderTest, ZeroSizesAreRefused) {
  ExpectInvalid(PngClaiming(0, 100), "frame.image is 0x100 pixels; an image has at least one");
  ExpectInvalid(PngClaiming(100, 0), "frame.image is 100x0 pixels; an image has at least one");
  ExpectInvalid(JpegClaiming(640, 0), "frame.image is 640x0 pixels; an image has at least one");
  ExpectInvalid(JpegClaiming(0, 0), "frame.image is 0x0 pixels; an image has at least one");
}

TEST(ImageHeaderTest, OtherFormatsAndGarbageAreRefusedListingTheAcceptedOnes) {
  const std::string message = "frame.image is not a PNG or JPEG image (the formats Orbit decodes)";
  ExpectInvalid("", message);
  ExpectInvalid("x", message);
  ExpectInvalid("not an image", message);
  ExpectInvalid(Encode(".bmp", Noise(8, 8, CV_8UC3)), message);
  ExpectInvalid(Encode(".tiff", Noise(8, 8, CV_8UC3)), message);
  ExpectInvalid(std::string("GIF89a\x10\x00\x10\x00", 10), message);
  ExpectInvalid("\xff\xd8", message);         // SOI alone is not what OpenCV calls a JPEG
  ExpectInvalid("\x89PNG\r\n\x1a", message);  // 7 of the signature's 8 bytes
}

TEST(ImageHeaderTest, TruncatedHeadersAreRefused) {
  const std::string png = Encode(".png", Noise(30, 20, CV_8UC3));
  for (std::size_t n = 8; n < 33; ++n) {
    ExpectInvalid(png.substr(0, n), "frame.image is a PNG whose header (IHDR) is truncated");
  }
  EXPECT_EQ(Read(png.substr(0, 33)).width, 30u);  // the IHDR is all the reader needs

  const std::string jpeg = kSoi + kApp0 + Sof(0xc0, 30, 20) + kEoi;
  const std::size_t sof_end = jpeg.size() - kEoi.size();
  for (std::size_t n = 3; n < sof_end; ++n) {
    ExpectInvalid(jpeg.substr(0, n),
                  "frame.image is a JPEG whose headers end before its frame header (SOF)");
  }
  EXPECT_EQ(Read(jpeg.substr(0, sof_end)).height, 20u);
}

TEST(ImageHeaderTest, MalformedPngHeadersAreRefused) {
  ExpectInvalid(kPngSignature + PngChunk("tEXt", std::string(13, 'a')) + Ihdr(10, 10),
                "frame.image is a PNG whose first chunk is not a 13-byte header (IHDR)");
  ExpectInvalid(kPngSignature + PngChunk("IHDR", std::string(14, '\0')),
                "frame.image is a PNG whose first chunk is not a 13-byte header (IHDR)");
  ExpectInvalid(PngClaiming(10, 10, 8, 5),
                "frame.image is a PNG whose header gives an unknown colour type 5");
  ExpectInvalid(
      PngClaiming(10, 10, 4, 2),
      "frame.image is a PNG whose header gives bit depth 4, not allowed for colour type 2");
  ExpectInvalid(
      PngClaiming(10, 10, 16, 3),
      "frame.image is a PNG whose header gives bit depth 16, not allowed for colour type 3");
  ExpectInvalid(PngClaiming(10, 10, 8, 2, 2),
                "frame.image is a PNG whose header gives an unknown compression, filter or "
                "interlace method");
  EXPECT_EQ(Read(PngClaiming(10, 12, 1, 0, 1)).height, 12u);  // 1-bit grey, Adam7
}

TEST(ImageHeaderTest, MalformedOrUnsupportedJpegHeadersAreRefused) {
  const std::string sof = Sof(0xc0, 64, 48);
  const std::string sos = JpegSegment(0xda, std::string("\1\1\0\0\x3f\0", 6));
  ExpectInvalid(kSoi + kApp0 + sos + sof + kEoi,
                "frame.image is a JPEG without a frame header (SOF) before its image data");
  ExpectInvalid(kSoi + kApp0 + kEoi,
                "frame.image is a JPEG without a frame header (SOF) before its image data");
  ExpectInvalid(kSoi + kApp0 + kSoi + sof,
                "frame.image is a JPEG with a second start-of-image marker");
  ExpectInvalid(kSoi + JpegSegment(0xf0, "x") + sof,
                "frame.image is a JPEG with an unknown marker 0xFFF0");
  ExpectInvalid(kSoi + std::string("\xff\xe0\x00\x01", 4) + sof,
                "frame.image is a JPEG with a marker segment shorter than 2 bytes");
  ExpectInvalid(kSoi + Sof(0xc3, 64, 48),
                "frame.image is a JPEG whose frame (marker 0xFFC3) is lossless, hierarchical or an "
                "extension; this server decodes baseline, extended and progressive JPEG");
  ExpectInvalid(kSoi + Sof(0xc1, 64, 48, 3, 12),
                "frame.image is a JPEG of 12-bit samples; this server decodes 8-bit JPEG");
  ExpectInvalid(kSoi + Sof(0xc0, 64, 48, 2),
                "frame.image is a JPEG of 2 components; this server decodes 1 (grey), 3 (colour) "
                "or 4 (CMYK)");
  std::string long_sof = Sof(0xc0, 64, 48, 1);
  long_sof[3] = static_cast<char>(long_sof[3] + 3);  // the length says one more component
  ExpectInvalid(kSoi + long_sof + std::string(3, '\0'),
                "frame.image is a JPEG whose frame header (SOF) has a wrong length");
  // Restart and TEM markers carry no length and are skipped; SOF9 (arithmetic) is read.
  EXPECT_EQ(Read(kSoi + "\xff\xd0\xff\x01" + Sof(0xc9, 64, 48)).width, 64u);
}

// A progressive grey 256x256 JPEG (libjpeg's default progression: 6 scans) followed by `extra`
// further scans of one EOB run each: a few bytes per scan, each a pass over every block.
std::string JpegWithExtraScans(int extra) {
  std::string jpeg = Encode(".jpg", Noise(256, 256, CV_8UC1), {cv::IMWRITE_JPEG_PROGRESSIVE, 1});
  jpeg.resize(jpeg.size() - kEoi.size());
  // AC table 0 with a single code, of length 1, for EOB run class 10 (runs of 1024..2047).
  jpeg += JpegSegment(0xc4, std::string{0x10, 1} + std::string(15, '\0') + "\xa0");
  for (int i = 0; i < extra; ++i) {
    // Component 1, tables 0/0, spectral selection 1..63, no successive approximation; then one
    // EOB run of 1024 blocks (code 0, 10 extra bits 0): all 32 x 32 blocks.
    jpeg += JpegSegment(0xda, std::string{1, 1, 0, 1, 63, 0}) + std::string(2, '\0');
  }
  return jpeg + kEoi;
}

TEST(ImageHeaderTest, CountsTheScansOfAJpegAndRefusesTooMany) {
  EXPECT_EQ(Read(Encode(".jpg", Noise(64, 64, CV_8UC3))).scans, 1);
  EXPECT_EQ(Read(Encode(".jpg", Noise(64, 64, CV_8UC3), {cv::IMWRITE_JPEG_PROGRESSIVE, 1})).scans,
            10);
  EXPECT_EQ(Read(JpegWithExtraScans(0)).scans, 6);
  // Stuffed 0xFF 0x00 bytes and restart markers in the entropy-coded data end no scan.
  const std::string restarts =
      Encode(".jpg", Noise(256, 256, CV_8UC3), {cv::IMWRITE_JPEG_RST_INTERVAL, 1});
  ASSERT_NE(restarts.find("\xff\xd7"), std::string::npos);
  ASSERT_NE(restarts.find(std::string("\xff\x00", 2)), std::string::npos);
  EXPECT_EQ(Read(restarts).scans, 1);
  // A thumbnail's scan inside APP1, and whatever follows EOI, are not the image's.
  const std::string thumbnail = Encode(".jpg", Noise(8, 8, CV_8UC3));
  const std::string baseline = Encode(".jpg", Noise(32, 32, CV_8UC3));
  EXPECT_EQ(Read(kSoi + JpegSegment(0xe1, std::string("Exif\0\0", 6) + thumbnail) +
                 baseline.substr(2) + JpegWithExtraScans(300))
                .scans,
            1);

  const std::string allowed = JpegWithExtraScans(kMaxJpegScans - 6);
  ExpectSizeAsDecoded(allowed, ImageFormat::kJpeg, 256, 256);  // libjpeg reads every extra scan
  EXPECT_EQ(Read(allowed).scans, 256);
  EXPECT_TRUE(CheckImageBudget(Read(allowed), kDefaultMax, "frame.image").ok());
  const grpc::Status refused =
      CheckImageBudget(Read(JpegWithExtraScans(kMaxJpegScans - 5)), kDefaultMax, "view.image");
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(refused.error_message(),
            "view.image is a JPEG of 257 scans; at most 256 are decoded (each is a pass over the "
            "whole image)");
}

// Whatever bytes a client sends, the reader never reports a size other than the one OpenCV
// decodes: single-byte changes, insertions and cuts of real images.
TEST(ImageHeaderTest, NeverDisagreesWithTheDecoderOnMutatedImages) {
  std::mt19937 random(13);
  const std::vector<std::string> originals = {
      Encode(".jpg", Noise(24, 16, CV_8UC3)),
      Encode(".jpg", Noise(16, 24, CV_8UC1), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}),
      Encode(".png", Noise(24, 16, CV_8UC3))};
  int agreed = 0;
  for (const std::string& original : originals) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string bytes = original;
      // Mutations land in the headers (the first 700 bytes), where the size is.
      const std::size_t at = random() % std::min<std::size_t>(bytes.size(), 700);
      switch (trial % 3) {
        case 0: bytes[at] = static_cast<char>(random()); break;
        case 1: bytes.insert(at, 1 + random() % 4, static_cast<char>(random())); break;
        default: bytes.erase(at, 1 + random() % 4);
      }
      ImageHeader header;
      if (!ReadImageHeader(bytes, "frame.image", &header).ok()) continue;
      if (std::uint64_t{header.width} * header.height > 1u << 24) continue;
      cv::Mat decoded;
      try {
        decoded = cv::imdecode(std::vector<std::uint8_t>(bytes.begin(), bytes.end()),
                               cv::IMREAD_UNCHANGED);
      } catch (const cv::Exception&) {
      }
      if (decoded.empty()) continue;
      EXPECT_EQ(static_cast<std::uint32_t>(decoded.cols), header.width) << "trial " << trial;
      EXPECT_EQ(static_cast<std::uint32_t>(decoded.rows), header.height) << "trial " << trial;
      ++agreed;
    }
  }
  EXPECT_GT(agreed, 100);  // the comparison ran, not only refusals
}

}  // namespace
}  // namespace orbit
