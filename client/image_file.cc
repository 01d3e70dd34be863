#include "client/image_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

namespace orbit {

namespace {

// The file's bytes and what its header says. Throws as ReadImageFile does for a missing or
// unreadable file and a header that is not a PNG's or JPEG's.
std::string ReadEncodedImage(const std::string& path, ImageHeader& header) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw std::runtime_error(path + ": no such file");
  }
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw std::runtime_error(path + ": cannot be read");
  if (grpc::Status s = ReadImageHeader(bytes, path, &header); !s.ok()) {
    throw std::runtime_error(s.error_message());
  }
  return bytes;
}

}  // namespace

cv::Size ReadImageSize(const std::string& path) {
  ImageHeader header;
  ReadEncodedImage(path, header);
  return cv::Size(static_cast<int>(header.width), static_cast<int>(header.height));
}

cv::Mat ReadImageFile(const std::string& path, std::int64_t max_pixels) {
  ImageHeader header;
  const std::string bytes = ReadEncodedImage(path, header);
  if (grpc::Status s = CheckImageBudget(header, max_pixels, path); !s.ok()) {
    throw std::runtime_error(s.error_message());
  }
  cv::Mat image = cv::imdecode(cv::_InputArray(bytes.data(), static_cast<int>(bytes.size())),
                               cv::IMREAD_UNCHANGED);
  if (image.empty()) throw std::runtime_error(path + ": not an image OpenCV can decode");
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 256);
  if (image.depth() != CV_8U ||
      (image.channels() != 1 && image.channels() != 3 && image.channels() != 4)) {
    throw std::runtime_error(path +
                             ": unsupported pixel format (need 8 or 16 bits, 1, 3 or 4 channels)");
  }
  return image;
}

}  // namespace orbit
