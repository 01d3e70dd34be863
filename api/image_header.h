// The image budget: what an image may cost whoever decodes it (the server for Frame.image and
// View.image, the device library and `orbit import` for files), checked before a single pixel is
// decoded.
//
// An encoded image says in its first bytes how large it is, and a decoder allocates and fills
// that many pixels: a 1.2 MB PNG can claim 20000x20000 pixels and cost 1.2 GB and seconds of CPU
// (docs/service.md, "Limits (flags of `orbit serve`)"). So the dimensions are read from the
// header itself, images above the budget are refused, and only then is anything decoded (the
// server also decodes at most one image per core at a time: server/decode_slots.h). A progressive
// JPEG can also repeat cheap scans, each a pass over every block of the image: a 4 MB message could
// hold 100000 of them, so the scans are counted too and bounded by kMaxJpegScans.
//
// Only PNG and JPEG are accepted: the two formats devices send, the two whose headers are read
// here. Every other format OpenCV could decode (TIFF, WebP, JPEG 2000, OpenEXR, ...) is refused
// before it reaches its decoder, which keeps those decoders' size rules and their bugs out of the
// server's attack surface.
#pragma once

#include <cstdint>
#include <string_view>

#include <grpcpp/grpcpp.h>

namespace orbit {

enum class ImageFormat { kPng, kJpeg };

// What an encoded image's header says, before anything is decoded.
struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  std::uint32_t width = 0;   // pixels, >= 1
  std::uint32_t height = 0;  // pixels, >= 1
  // JPEG: the scans (SOS markers) before EOI, each one decoding pass; PNG: 1.
  int scans = 1;
};

// The most scans a JPEG may have. Encoders write 1 to 4 for baseline JPEG and about 10 for
// progressive (libjpeg's default progression: 10 scans for colour, 6 for grey); 256 is the bound
// NVIDIA's nvImageCodec sets against the same attack (NVIMGCODEC_MAX_JPEG_SCANS, after Cure53's
// review of libjpeg-turbo). A scan without data is one pass over the image, so the bound caps
// them at 256 passes; a scan with data costs what its bytes do, bounded by the message size.
inline constexpr int kMaxJpegScans = 256;

// The default budget, width x height: 4096 x 4096 passes a 12 MP phone photo (4032 x 3024), a 4K
// frame (3840 x 2160) and anything smaller, while a decoded image stays under 128 MiB (at most 8
// bytes a pixel: 4 channels of 16 bits). The server's --max-image-pixels starts here.
inline constexpr std::int64_t kDefaultMaxImagePixels = std::int64_t{4096} * 4096;

// Reads the dimensions of an encoded image from its header:
//  - PNG: the IHDR chunk, which the format requires first and libpng takes as the only header;
//  - JPEG (8-bit baseline, extended or progressive, 1, 3 or 4 components): the first frame
//    header (SOF0, SOF1, SOF2, SOF9 or SOF10), found by walking the marker segments exactly as
//    libjpeg does (skipping each segment by its length, so an EXIF thumbnail's own SOF inside
//    APP1 is never mistaken for the image's; stray bytes between segments skipped as libjpeg
//    skips them); then the rest of the stream the same way, to count the scans libjpeg would
//    start (never fewer).
// Whatever libjpeg or libpng would read differently (a second SOI, an unknown marker, a segment
// length below 2, a first chunk other than IHDR, an IHDR field the PNG specification forbids) is
// refused rather than guessed at, so the dimensions read here are those the decoder allocates.
//
// OK with *out filled; else INVALID_ARGUMENT whose message names `field` (e.g. "frame.image") and
// says what is wrong: another format (the message lists the accepted ones), a truncated or
// malformed header, a coding process or sample precision the decoder does not support, zero
// width or height. Never reads past `bytes`; costs one pass over a JPEG's bytes (a memchr for
// 0xFF) and 33 bytes of a PNG, whatever size either claims. Pure, thread-safe.
grpc::Status ReadImageHeader(std::string_view bytes, std::string_view field, ImageHeader* out);

// OK when header.width x header.height <= max_pixels (computed without overflow: both sides are
// below 2^32) and header.scans <= kMaxJpegScans; else RESOURCE_EXHAUSTED naming `field`, the
// image's size and the maximum, e.g.
// "frame.image is 20000x20000 pixels; at most 16777216 pixels (4096x4096) are decoded", or its
// scans and the maximum.
//
// RESOURCE_EXHAUSTED, not INVALID_ARGUMENT: the image is well formed and only what this server
// spends on one image (orbit serve --max-image-pixels) refuses it, as with the message-size and
// window limits; a client may downscale (or re-encode) and send again. Pure, thread-safe.
grpc::Status CheckImageBudget(const ImageHeader& header, std::int64_t max_pixels,
                              std::string_view field);

}  // namespace orbit
