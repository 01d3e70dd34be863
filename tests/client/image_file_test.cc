// Reading image files (client/image_file.h): real PNG and JPEG files decoded as OpenCV decodes
// them, and the image budget applied from the header before anything is decoded.
#include "client/image_file.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::DataDir;
using testing::ScratchDir;

std::string ErrorOf(const std::string& path, std::int64_t max_pixels = kDefaultMaxImagePixels) {
  try {
    ReadImageFile(path, max_pixels);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageFileTest, ReadsRealPngAndJpegFilesAsOpenCvDecodesThem) {
  for (const std::string file : {(DataDir() / "coil-100" / "obj1__0.png").string(),
                                 (DataDir() / "epfl-cars" / "images" / "car01_001.jpg").string()}) {
    const cv::Mat read = ReadImageFile(file);
    const cv::Mat reference = cv::imread(file, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(reference.empty()) << file;
    ASSERT_EQ(read.size(), reference.size()) << file;
    ASSERT_EQ(read.type(), reference.type()) << file;
    EXPECT_EQ(cv::norm(read, reference, cv::NORM_INF), 0) << file;
  }
}

// A 5000 x 4000 PNG of one colour is a few tens of KB on disk and 57 MiB once decoded: refused
// from its header under the default budget, read under a larger one.
TEST(ImageFileTest, RefusesAnImageAboveTheBudgetBeforeDecodingIt) {
  ScratchDir dir;
  const std::string large = (dir / "large.png").string();
  ASSERT_TRUE(cv::imwrite(large, cv::Mat(4000, 5000, CV_8UC3, cv::Scalar(10, 20, 30))));
  EXPECT_EQ(ErrorOf(large), large +
                                " is 5000x4000 pixels; at most 16777216 pixels (4096x4096) "
                                "are decoded");
  EXPECT_EQ(ReadImageFile(large, 20'000'000).size(), cv::Size(5000, 4000));
}

TEST(ImageFileTest, RefusesOtherFormatsAndMissingFilesNamingThem) {
  ScratchDir dir;
  const std::string bmp = (dir / "picture.bmp").string();
  ASSERT_TRUE(cv::imwrite(bmp, cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3))));
  EXPECT_EQ(ErrorOf(bmp), bmp + " is not a PNG or JPEG image (the formats Orbit decodes)");
  const std::string missing = (dir / "none.png").string();
  EXPECT_EQ(ErrorOf(missing), missing + ": no such file");
}

}  // namespace
}  // namespace orbit
