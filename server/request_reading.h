// Requests read into the values of core/ and storage/, with the checks that only the server
// makes (docs/design.md#service-behaviour): the variant of a request against the
// server's, uploaded images decoded and described here. The conversions both ends share are in
// api/conversion.h. Every refusal names the field and says what is wrong; it is INVALID_ARGUMENT,
// except an image above the server's pixel limit (RESOURCE_EXHAUSTED, api/image_header.h).
// Thread-safe; pure but for the process's decode slots, which an image decode waits for.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "core/engines/recognition_engine.h"
#include "core/model/object_model.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"
#include "server/session_settings.h"

namespace orbit::server {

// OK when `requested` is unspecified or equals `server`; else INVALID_ARGUMENT naming both.
grpc::Status CheckVariant(v1::DescriptorVariant requested, DescriptorVariant server,
                          std::string_view field);

// A frame as the engines take it. With `cedd`: exactly 144 values, each 0..7. With `image`: a PNG
// or JPEG of at most limits.max_image_pixels pixels, read from its header before anything is
// decoded (api/image_header.h; RESOURCE_EXHAUSTED above it), then decoded (waiting for one of
// the process's decode slots, held until the descriptor is computed) and its CEDD (of `region`
// when set, which must lie inside it) computed in the server's variant. The azimuth must be
// finite; quality.noise_sigma, when quality is set, in [0, 255] and quality.blur in [0, 1] (the
// calibrated rule's allowance reads them, core/decision/quality_allowance.h). An image frame
// without quality has both measured here, on the region.
grpc::Status ToQueryFrame(const v1::Frame& frame, DescriptorVariant variant,
                          const ServerLimits& limits, QueryFrame* out);

// A view as the store keeps it. With `cedd`, the typical distance is taken from the message
// (0, unknown, when absent; else it must be in [0, 1]); with `image` (within `limits` as a
// frame's image is), the server describes the image (or its region) as every enrollment path
// does (core/descriptor/view_description.h, DescribeView with the default seed), so an uploaded
// image stores what the client library would have sent. `thumbnail` receives the view's thumbnail
// bytes (at most 64 KiB).
grpc::Status ToModelView(const v1::View& view, DescriptorVariant variant,
                         const ServerLimits& limits, ModelView* out, std::string* thumbnail);

// The views of an enrollment or of AddViews, each read by ToModelView and appended to *views;
// *thumbnails receives one per view, or none when no view has one. The first refusal is
// returned with "view I: " before its message (I counting from 0).
grpc::Status ToModelViews(const std::vector<v1::View>& wire, DescriptorVariant variant,
                          const ServerLimits& limits, std::vector<ModelView>* views,
                          std::vector<std::string>* thumbnails);

}  // namespace orbit::server
