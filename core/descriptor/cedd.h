// The CEDD extractor (docs/design.md#cedd): colour and edge directivity descriptor of an image
// region.
//
// Thread-safe: ExtractCedd keeps no state between calls.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "core/descriptor/descriptor.h"

namespace orbit {

// Extracts the CEDD of `image`, or of `roi` inside it when given.
//
// image: CV_8UC3 (BGR, OpenCV's order), CV_8UC1 (grey: the value is used for R, G and B) or
// CV_8UC4 (BGRA: composited over black first, c' = round(c * a / 255), as LIRE does).
// variant:
//   kCeddLire  bit-exact with LIRE: blocks on LIRE's grid, so pixels right of or below the grid
//              are ignored (the bottom-right 48 columns and rows of a 128x128 image); a region
//              1 pixel wide or tall has no blocks and gives all zeros.
//   kCeddFull  a 40x40 grid whose block edges are at floor(i * width / 40) and
//              floor(i * height / 40), so every pixel counts; quadrant means are the exact
//              truncated means over the pixels each quadrant really has. A region under 40
//              pixels on a side gets one block per pixel along that side, and a block one pixel
//              wide (tall) uses its single column (row) for both its left and right (top and
//              bottom) quadrants, which therefore show no edge across it. So every non-empty
//              region, even 1x1, gets a descriptor of its colours.
//   kCeddRobust kCeddFull of CanonicalFrame(region) (core/descriptor/canonical_frame.h).
//
// Throws std::invalid_argument when the image is empty or of another type, or when the region
// is empty or not inside the image.
Descriptor ExtractCedd(const cv::Mat& image, DescriptorVariant variant,
                       std::optional<cv::Rect> roi = std::nullopt);

}  // namespace orbit
