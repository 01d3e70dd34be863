// Fuzz target: the CEDD extractor (core/descriptor/cedd.h, ExtractCedd) on arbitrary pixels: any
// size up to 128 x 128 (a COIL-100 image; past LIRE's grid modes at 40 and 80 pixels and the full
// variant's one block per pixel under 40), any type (the three it takes and two it must refuse),
// either variant, with or without a region (inside the image or not), in a continuous buffer or
// as a view into a wider one.
//
// Input: 4 bytes of shape ((width - 1) mod 128, (height - 1) mod 128, type, flags: bit 0 the
// variant, bit 1 a region, bit 2 a view into a wider buffer), then 4 bytes of region (x, y,
// width, height) when bit 1 is set, then the pixel bytes, repeated to fill the image (zeros when
// there are none).
//
// Checked beyond "no crash": only std::invalid_argument is thrown, for the types and regions
// core/descriptor/cedd.h refuses and no others; the descriptor has the requested variant and values
// in 0..7; and the CEDD of a region, or of an image held as a view into a wider buffer, equals the
// CEDD of a continuous copy of the same pixels.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "core/descriptor/cedd.h"
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  if (size < 4) return 0;
  const int width = 1 + data[0] % 128, height = 1 + data[1] % 128;
  constexpr int kTypes[] = {CV_8UC1, CV_8UC3, CV_8UC4, CV_8UC2, CV_16UC3};
  const int type = kTypes[data[2] % 5];
  const bool accepted_type = data[2] % 5 < 3;
  const DescriptorVariant variant =
      (data[3] & 1) ? DescriptorVariant::kCeddFull : DescriptorVariant::kCeddLire;
  const bool has_roi = data[3] & 2, as_view = data[3] & 4;
  std::size_t at = 4;
  std::optional<cv::Rect> roi;
  if (has_roi) {
    if (size < 8) return 0;
    roi = cv::Rect(data[4], data[5], data[6], data[7]);
    at = 8;
  }

  // The pixels, as a view into a buffer 3 columns wider (and 1 row taller) when asked.
  cv::Mat buffer(height + (as_view ? 1 : 0), width + (as_view ? 3 : 0), type, cv::Scalar::all(0));
  cv::Mat image = buffer(cv::Rect(as_view ? 2 : 0, as_view ? 1 : 0, width, height));
  if (at < size) {
    std::size_t next = at;
    for (int y = 0; y < height; ++y) {
      std::uint8_t* row = image.ptr<std::uint8_t>(y);
      for (std::size_t i = 0; i < image.cols * image.elemSize(); ++i) {
        row[i] = data[next];
        next = next + 1 < size ? next + 1 : at;
      }
    }
  }

  const bool roi_inside =
      roi && roi->width > 0 && roi->height > 0 && (*roi & cv::Rect(0, 0, width, height)) == *roi;
  const bool accepted = accepted_type && (!roi || roi_inside);
  Descriptor descriptor;
  try {
    descriptor = ExtractCedd(image, variant, roi);
  } catch (const std::invalid_argument&) {
    ORBIT_FUZZ_CHECK(!accepted);
    return 0;
  }
  ORBIT_FUZZ_CHECK(accepted);
  ORBIT_FUZZ_CHECK(descriptor.variant == variant);
  for (std::uint8_t value : descriptor.values) ORBIT_FUZZ_CHECK(value <= kDescriptorMaxValue);
  if (roi || as_view) {
    const cv::Mat copy = (roi ? image(*roi) : image).clone();
    ORBIT_FUZZ_CHECK(ExtractCedd(copy, variant) == descriptor);
  }
  return 0;
}
