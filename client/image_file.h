// Reading images from files for the descriptor: decoded as the LIRE reference decodes them, so
// that `cedd-lire` descriptors of the same file agree.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace orbit {

// Reads an image file (PNG, JPEG, BMP, TIFF, ... whatever OpenCV's imgcodecs reads) without any
// colour conversion or EXIF rotation: CV_8UC1 for grey, CV_8UC3 (BGR) for colour, CV_8UC4 (BGRA)
// with alpha; 16-bit images are reduced to their high byte. The result is ready for ExtractCedd.
//
// Throws std::runtime_error naming the file when it cannot be read or decoded.
cv::Mat ReadImageFile(const std::string& path);

}  // namespace orbit
