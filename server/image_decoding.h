// An uploaded image (Frame.image, View.image) decoded as the server decodes it: its header read
// and held to the image budget first (api/image_header.h), then one of the process's decode
// slots taken, then OpenCV's PNG or JPEG decoder run on the bytes in place.
#pragma once

#include <cstdint>
#include <string_view>

#include <grpcpp/grpcpp.h>
#include <opencv2/core.hpp>

#include "api/image_header.h"
#include "server/decode_slots.h"

namespace orbit::server {

// A decoded image with the decode slot it holds. Members are destroyed in reverse order, so the
// slot is given back only once the pixels are freed.
struct DecodedImage {
  DecodeSlots::Slot slot;
  cv::Mat pixels;
};

// Decodes `bytes`, the request's `field`. Refusals come before anything is decoded, as
// ReadImageHeader (INVALID_ARGUMENT) and CheckImageBudget against `max_pixels`
// (RESOURCE_EXHAUSTED) give them; only then does the decode wait for one of ProcessDecodeSlots,
// which out->slot holds until *out is destroyed. Data the decoder cannot read is
// INVALID_ARGUMENT "<field> cannot be decoded: its PNG (JPEG) data is corrupt or truncated".
// On OK, out->pixels has the width and height the header gave (ReadImageHeader reads what the
// decoder allocates), 1, 3 or 4 channels as the file has them (BGR order, no EXIF rotation), 8
// bits each: 16-bit samples are scaled down by 256. Thread-safe.
grpc::Status DecodeImage(std::string_view bytes, std::string_view field, std::int64_t max_pixels,
                         DecodedImage* out);

}  // namespace orbit::server
