// Reading images from files for the descriptor: decoded as the LIRE reference decodes them, so
// that `cedd-lire` descriptors of the same file agree, and held to the same image budget as the
// server's uploads (api/image_header.h), so that a small file claiming a huge image costs nothing.
#pragma once

#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "api/image_header.h"

namespace orbit {

// Reads a PNG or JPEG file without any colour conversion or EXIF rotation: CV_8UC1 for grey,
// CV_8UC3 (BGR) for colour, CV_8UC4 (BGRA) with alpha; 16-bit images are reduced to their high
// byte. The result is ready for ExtractCedd. Its width x height is read from the header first
// (ReadImageHeader) and an image above `max_pixels`, or a JPEG of more than kMaxJpegScans scans,
// is refused before anything is decoded.
//
// Throws std::runtime_error naming the file when it cannot be read, is not a PNG or JPEG, has a
// malformed header, is above the budget or cannot be decoded.
cv::Mat ReadImageFile(const std::string& path, std::int64_t max_pixels = kDefaultMaxImagePixels);

// The width x height of a PNG or JPEG file as its header states it, nothing decoded: what
// ReadImageFile would return, for checking a box against an image before any work is done.
// Throws std::runtime_error as ReadImageFile does for a file it cannot read or a bad header.
cv::Size ReadImageSize(const std::string& path);

}  // namespace orbit
