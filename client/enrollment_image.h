// EnrollmentImage: one image of an object to enroll, with where the camera stood.
#pragma once

#include <opencv2/core.hpp>
#include <optional>

namespace orbit {

struct EnrollmentImage {
  cv::Mat image;                   // as ExtractCedd accepts (BGR, grey or BGRA, 8-bit)
  double azimuth_deg = 0;          // where the camera stood, in degrees
  std::optional<cv::Rect> region;  // the object's region; the whole image when unset
  std::optional<double> elevation_deg;
};

}  // namespace orbit
