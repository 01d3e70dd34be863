// Fuzz target: an uploaded image as the server takes it (api/image_header.h,
// server/image_decoding.h): its header read (PNG's IHDR; JPEG's marker segments up to the frame
// header, then its scans counted), held to the budget (CheckImageBudget), decoded by OpenCV's
// PNG or JPEG decoder, and described as a frame is (core/descriptor/cedd.h, ExtractCedd).
//
// Input: the encoded image's bytes. The seeds (corpus/image_decode/) are small PNGs (grey,
// palette, RGB, RGBA, 16-bit, interlaced) and JPEGs (baseline, progressive, grey, with EXIF and
// restart markers), and headers at the edge of what the reader accepts.
//
// Checked beyond "no crash": what the budget rests on, that the decoder allocates exactly the
// pixels the header reader said (an image it decodes has the header's width and height, so no
// image can pass the budget and decode larger), and that a header within the limit passes the
// budget unless it has too many scans.
//
// OpenCV, libpng and libjpeg are Debian's uninstrumented builds: their code gets no coverage
// feedback here and their memory errors are found only as crashes; the header reader, the budget
// and CEDD are instrumented.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "api/image_header.h"
#include "core/descriptor/cedd.h"
#include "fuzz/fuzz_support.h"
#include "server/image_decoding.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  static const std::int64_t max_pixels = fuzz::FuzzLimits().max_image_pixels;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);

  ImageHeader header;
  if (!ReadImageHeader(bytes, "frame.image", &header).ok()) return 0;
  ORBIT_FUZZ_CHECK(header.width >= 1 && header.height >= 1);
  ORBIT_FUZZ_CHECK(header.scans >= 0);
  const bool within = std::uint64_t{header.width} * header.height <= std::uint64_t(max_pixels) &&
                      header.scans <= kMaxJpegScans;
  ORBIT_FUZZ_CHECK(CheckImageBudget(header, max_pixels, "frame.image").ok() == within);
  if (!within) return 0;

  server::DecodedImage image;
  if (!server::DecodeImage(bytes, "frame.image", max_pixels, &image).ok()) return 0;
  const cv::Mat& pixels = image.pixels;
  if (static_cast<std::uint32_t>(pixels.cols) != header.width ||
      static_cast<std::uint32_t>(pixels.rows) != header.height) {
    std::fprintf(stderr, "header %ux%u, decoded %dx%d\n", header.width, header.height, pixels.cols,
                 pixels.rows);
    ORBIT_FUZZ_CHECK(false);
  }
  ORBIT_FUZZ_CHECK(pixels.depth() == CV_8U);
  ORBIT_FUZZ_CHECK(pixels.channels() == 1 || pixels.channels() == 3 || pixels.channels() == 4);
  const Descriptor descriptor = ExtractCedd(pixels, DescriptorVariant::kCeddLire);
  for (std::uint8_t value : descriptor.values) ORBIT_FUZZ_CHECK(value <= kDescriptorMaxValue);
  return 0;
}
