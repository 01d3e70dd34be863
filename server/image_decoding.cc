#include "server/image_decoding.h"

#include <string>

#include <opencv2/imgcodecs.hpp>

#include "server/error_status.h"

namespace orbit::server {

grpc::Status DecodeImage(std::string_view bytes, std::string_view field, std::int64_t max_pixels,
                         DecodedImage* out) {
  ImageHeader header;
  if (auto s = ReadImageHeader(bytes, field, &header); !s.ok()) return s;
  if (auto s = CheckImageBudget(header, max_pixels, field); !s.ok()) return s;
  out->slot = ProcessDecodeSlots().Acquire();
  cv::Mat& image = out->pixels;
  // The request's bytes, read in place (imdecode does not write to its input): no copy.
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
  try {
    image = cv::imdecode(encoded, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) {
    return InvalidArgument(std::string(field) + " cannot be decoded: its " +
                           (header.format == ImageFormat::kPng ? "PNG" : "JPEG") +
                           " data is corrupt or truncated");
  }
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 256);
  return grpc::Status::OK;
}

}  // namespace orbit::server
