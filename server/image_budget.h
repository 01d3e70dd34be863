// The image budget: what an uploaded image (Frame.image, View.image) may cost the server, checked
// before a single pixel is decoded.
//
// An encoded image says in its first bytes how large it is, and a decoder allocates and fills
// that many pixels: a 1.2 MB PNG can claim 20000x20000 pixels and cost 1.2 GB and seconds of CPU
// (docs/service.md, "Limits (flags of `orbit serve`)"). So the server reads the dimensions from
// the header itself, refuses images above ServerLimits::max_image_pixels, and only then decodes;
// and at most one image per core is decoded at a time across the process (DecodeSlots), so
// several large-but-allowed images cannot take every worker's memory at once. A progressive JPEG
// can also repeat cheap scans, each a pass over every block of the image: a 4 MB message could
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

#include "core/base/mutex.h"

namespace orbit::server {

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

// A counting semaphore over decodes: at most `slots` holders at once; Acquire() blocks (on a
// condition variable: it sleeps, it never spins) until one is free. A slot is held for the whole
// life of a decoded image (decode, then description), so `slots` x ServerLimits::max_image_pixels
// x 8 bytes (4 channels of 16 bits, the most OpenCV decodes a PNG or JPEG to) bounds the
// memory decoded images hold at once. Holders must not wait for anything else while holding a
// slot (no deadlock is possible then). Thread-safe.
class DecodeSlots {
 public:
  // A held slot, released when destroyed. Movable; an empty (default or moved-from) Slot holds
  // nothing.
  class [[nodiscard]] Slot {
   public:
    Slot() = default;
    Slot(Slot&& other) noexcept : owner_(other.owner_) { other.owner_ = nullptr; }
    Slot& operator=(Slot&& other) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class DecodeSlots;
    explicit Slot(DecodeSlots* owner) : owner_(owner) {}
    DecodeSlots* owner_ = nullptr;
  };

  // REQUIRES: slots >= 1.
  explicit DecodeSlots(int slots);
  // REQUIRES: no Slot of this object is held.
  ~DecodeSlots() = default;

  DecodeSlots(const DecodeSlots&) = delete;
  DecodeSlots& operator=(const DecodeSlots&) = delete;

  // Waits until a slot is free, then holds it.
  Slot Acquire() ABSL_LOCKS_EXCLUDED(mutex_);

  // The number of slots, held or free.
  int capacity() const { return capacity_; }

 private:
  void Release() ABSL_LOCKS_EXCLUDED(mutex_);

  const int capacity_;
  Mutex mutex_;
  CondVar freed_;
  int free_ ABSL_GUARDED_BY(mutex_);
};

// The decode slots every image decoded by this process goes through: one per core
// (AvailableCpus, core/base/parallel_for.h: the CPUs this process may run on). Decoding is
// CPU-bound, so more decodes at once than cores would not finish sooner; they would only hold more
// memory. The worker pool already bounds decodes by its size; these slots keep the bound when
// --workers is above the core count.
DecodeSlots& ProcessDecodeSlots();

}  // namespace orbit::server
