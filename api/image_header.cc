#include "api/image_header.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

namespace orbit {
namespace {

constexpr std::string_view kAccepted = "PNG or JPEG";
constexpr std::string_view kPngSignature = "\x89PNG\r\n\x1a\n";
// What OpenCV's JPEG decoder recognises a JPEG by: SOI, then the first byte of a marker.
constexpr std::string_view kJpegSignature = "\xff\xd8\xff";

std::uint8_t Byte(std::string_view bytes, std::size_t at) {
  return static_cast<std::uint8_t>(bytes[at]);
}

// REQUIRES: at + 2 <= bytes.size().
std::uint32_t BigEndian16(std::string_view bytes, std::size_t at) {
  return std::uint32_t{Byte(bytes, at)} << 8 | Byte(bytes, at + 1);
}

// REQUIRES: at + 4 <= bytes.size().
std::uint32_t BigEndian32(std::string_view bytes, std::size_t at) {
  return BigEndian16(bytes, at) << 16 | BigEndian16(bytes, at + 2);
}

grpc::Status InvalidArgument(std::string message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, std::move(message)};
}

grpc::Status Malformed(std::string_view field, std::string_view what) {
  return InvalidArgument(std::string(field) + " is " + std::string(what));
}

// PNG: the 8-byte signature, then the IHDR chunk (length 13, "IHDR", width, height, bit depth,
// colour type, compression, filter, interlace, CRC). The CRC is not checked: libpng refuses a
// wrong one before decoding anything, so a wrong CRC cannot make the decoder see other
// dimensions.
grpc::Status ReadPngHeader(std::string_view bytes, std::string_view field, ImageHeader* out) {
  constexpr std::size_t kIhdrEnd = 8 + 4 + 4 + 13 + 4;
  if (bytes.size() < kIhdrEnd) {
    return Malformed(field, "a PNG whose header (IHDR) is truncated");
  }
  if (BigEndian32(bytes, 8) != 13 || bytes.substr(12, 4) != "IHDR") {
    return Malformed(field, "a PNG whose first chunk is not a 13-byte header (IHDR)");
  }
  const std::uint32_t width = BigEndian32(bytes, 16), height = BigEndian32(bytes, 20);
  const int depth = Byte(bytes, 24), colour = Byte(bytes, 25);
  // The PNG specification's (and libpng's) rules: sizes are 31-bit, and each colour type allows
  // only some bit depths.
  if (width > 0x7fffffffu || height > 0x7fffffffu) {
    return Malformed(field, "a PNG whose header gives a width or height above 2^31 - 1");
  }
  bool depth_allowed = false;
  switch (colour) {
    case 0:  // greyscale
      depth_allowed = depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
      break;
    case 3:  // palette
      depth_allowed = depth == 1 || depth == 2 || depth == 4 || depth == 8;
      break;
    case 2:  // RGB
    case 4:  // greyscale and alpha
    case 6:  // RGBA
      depth_allowed = depth == 8 || depth == 16;
      break;
    default:
      return Malformed(field,
                       "a PNG whose header gives an unknown colour type " + std::to_string(colour));
  }
  if (!depth_allowed) {
    return Malformed(field, "a PNG whose header gives bit depth " + std::to_string(depth) +
                                ", not allowed for colour type " + std::to_string(colour));
  }
  if (Byte(bytes, 26) != 0 || Byte(bytes, 27) != 0 || Byte(bytes, 28) > 1) {
    return Malformed(field,
                     "a PNG whose header gives an unknown compression, filter or interlace method");
  }
  *out = {ImageFormat::kPng, width, height, 1};
  return grpc::Status::OK;
}

// "0xFFC3" for marker code 0xC3.
std::string MarkerName(std::uint8_t code) {
  constexpr char kDigits[] = "0123456789ABCDEF";
  return std::string("0xFF") + kDigits[code >> 4] + kDigits[code & 15];
}

// libjpeg's next_marker(), which also finds the marker that ends a scan's entropy-coded data as
// its Huffman decoder does: skips any bytes up to an 0xFF, then 0xFF fill bytes; 0xFF 0x00 is
// stuffed data, skipped too. Returns the marker code after it, with *at just past it; nullopt
// when the bytes end first.
std::optional<std::uint8_t> NextJpegMarker(std::string_view bytes, std::size_t* at) {
  for (;;) {
    *at = std::min(bytes.find('\xff', *at), bytes.size());
    while (*at < bytes.size() && Byte(bytes, *at) == 0xff) ++*at;
    if (*at == bytes.size()) return std::nullopt;
    const std::uint8_t code = Byte(bytes, (*at)++);
    if (code != 0) return code;
  }
}

// Markers that stand alone: RSTn and TEM.
bool IsStandaloneMarker(std::uint8_t m) { return (m >= 0xd0 && m <= 0xd7) || m == 0x01; }

// Markers whose segment libjpeg reads or skips, and nothing more: DHT, DAC, DQT, DNL, DRI, APPn,
// COM.
bool IsTableOrMiscMarker(std::uint8_t m) {
  return m == 0xc4 || m == 0xcc || (m >= 0xdb && m <= 0xdd) || (m >= 0xe0 && m <= 0xef) ||
         m == 0xfe;
}

// The scans (SOS markers) libjpeg can start from `at` (just past the frame header) on: markers
// found as libjpeg finds them, past segments (by their length) and past entropy-coded data.
// Counting stops at EOI, at the end of the bytes, and wherever libjpeg would stop with an error
// (a second SOI or SOF, an unknown marker, a segment shorter than 2 bytes or running past the
// end), so libjpeg never decodes more scans than this.
int CountJpegScans(std::string_view bytes, std::size_t at) {
  int scans = 0;
  while (const std::optional<std::uint8_t> marker = NextJpegMarker(bytes, &at)) {
    const std::uint8_t m = *marker;
    if (IsStandaloneMarker(m)) continue;
    if (m != 0xda && !IsTableOrMiscMarker(m)) break;
    if (at + 2 > bytes.size()) break;
    const std::uint32_t length = BigEndian16(bytes, at);
    if (length < 2 || at + length > bytes.size()) break;
    if (m == 0xda) ++scans;
    at += length;
  }
  return scans;
}

// JPEG: SOI, then marker segments up to the first frame header (SOFn), as libjpeg's
// read_markers() walks them (whatever it would stop at with an error is refused here); then the
// rest of the stream, to count its scans.
grpc::Status ReadJpegHeader(std::string_view bytes, std::string_view field, ImageHeader* out) {
  const std::string truncated = "a JPEG whose headers end before its frame header (SOF)";
  std::size_t at = 2;  // after SOI
  for (;;) {
    const std::optional<std::uint8_t> marker = NextJpegMarker(bytes, &at);
    if (!marker) return Malformed(field, truncated);
    const std::uint8_t m = *marker;
    if (IsStandaloneMarker(m)) continue;
    if (m == 0xd8) return Malformed(field, "a JPEG with a second start-of-image marker");
    if (m == 0xda || m == 0xd9) {
      return Malformed(field, "a JPEG without a frame header (SOF) before its image data");
    }
    const bool supported_frame = m == 0xc0 || m == 0xc1 || m == 0xc2 || m == 0xc9 || m == 0xca;
    const bool other_frame = m >= 0xc3 && m <= 0xcf && !IsTableOrMiscMarker(m) && !supported_frame;
    if (other_frame) {
      return Malformed(field, "a JPEG whose frame (marker " + MarkerName(m) +
                                  ") is lossless, hierarchical or an extension; this server "
                                  "decodes baseline, extended and progressive JPEG");
    }
    if (!supported_frame && !IsTableOrMiscMarker(m)) {
      return Malformed(field, "a JPEG with an unknown marker " + MarkerName(m));
    }
    if (at + 2 > bytes.size()) return Malformed(field, truncated);
    const std::uint32_t length = BigEndian16(bytes, at);  // counts itself, not the marker
    if (length < 2) return Malformed(field, "a JPEG with a marker segment shorter than 2 bytes");
    if (at + length > bytes.size()) return Malformed(field, truncated);
    if (!supported_frame) {
      at += length;
      continue;
    }
    // SOF: length, precision, height, width, component count, then 3 bytes per component.
    const int components = length >= 8 ? Byte(bytes, at + 7) : 0;
    if (length < 8 || length != 8u + 3u * static_cast<unsigned>(components)) {
      return Malformed(field, "a JPEG whose frame header (SOF) has a wrong length");
    }
    if (const int precision = Byte(bytes, at + 2); precision != 8) {
      return Malformed(field, "a JPEG of " + std::to_string(precision) +
                                  "-bit samples; this server decodes 8-bit JPEG");
    }
    if (components != 1 && components != 3 && components != 4) {
      return Malformed(field, "a JPEG of " + std::to_string(components) +
                                  " components; this server decodes 1 (grey), 3 (colour) or 4 "
                                  "(CMYK)");
    }
    *out = {ImageFormat::kJpeg, BigEndian16(bytes, at + 5), BigEndian16(bytes, at + 3),
            CountJpegScans(bytes, at + length)};
    return grpc::Status::OK;
  }
}

}  // namespace

grpc::Status ReadImageHeader(std::string_view bytes, std::string_view field, ImageHeader* out) {
  grpc::Status status;
  if (bytes.substr(0, kPngSignature.size()) == kPngSignature) {
    status = ReadPngHeader(bytes, field, out);
  } else if (bytes.substr(0, kJpegSignature.size()) == kJpegSignature) {
    status = ReadJpegHeader(bytes, field, out);
  } else {
    return InvalidArgument(std::string(field) + " is not a " + std::string(kAccepted) +
                           " image (the formats Orbit decodes)");
  }
  if (status.ok() && (out->width == 0 || out->height == 0)) {
    return InvalidArgument(std::string(field) + " is " + std::to_string(out->width) + "x" +
                           std::to_string(out->height) + " pixels; an image has at least one");
  }
  return status;
}

grpc::Status CheckImageBudget(const ImageHeader& header, std::int64_t max_pixels,
                              std::string_view field) {
  // Both factors are below 2^32, so the product fits in 64 bits unsigned.
  const std::uint64_t pixels = std::uint64_t{header.width} * header.height;
  if (max_pixels < 0 || pixels > static_cast<std::uint64_t>(max_pixels)) {
    std::string message = std::string(field) + " is " + std::to_string(header.width) + "x" +
                          std::to_string(header.height) + " pixels; at most " +
                          std::to_string(max_pixels) + " pixels";
    // A square maximum is also shown as its side. Up to 2^53 the square root of a perfect
    // square is exact in a double.
    if (max_pixels > 0 && max_pixels <= (std::int64_t{1} << 53)) {
      const auto side = std::llround(std::sqrt(static_cast<double>(max_pixels)));
      if (side * side == max_pixels) {
        message += " (" + std::to_string(side) + "x" + std::to_string(side) + ")";
      }
    }
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, message + " are decoded"};
  }
  if (header.scans > kMaxJpegScans) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            std::string(field) + " is a JPEG of " + std::to_string(header.scans) +
                " scans; at most " + std::to_string(kMaxJpegScans) +
                " are decoded (each is a pass over the whole image)"};
  }
  return grpc::Status::OK;
}

}  // namespace orbit
