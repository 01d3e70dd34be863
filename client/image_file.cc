#include "client/image_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

namespace orbit {

cv::Mat ReadImageFile(const std::string& path, std::int64_t max_pixels) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw std::runtime_error(path + ": no such file");
  }
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw std::runtime_error(path + ": cannot be read");
  ImageHeader header;
  if (grpc::Status s = ReadImageHeader(bytes, path, &header); !s.ok()) {
    throw std::runtime_error(s.error_message());
  }
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
