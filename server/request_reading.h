// Requests read into the values of core/ and storage/, with the checks SPEC.md's "Service
// behaviour" asks for and that only the server makes: the variant of a request against the
// server's, uploaded images decoded and described here. The conversions both ends share are in
// api/conversion.h. Every refusal is INVALID_ARGUMENT with a message that names the field and
// says what is wrong. Pure functions, thread-safe.
#pragma once

#include <string>
#include <string_view>

#include <grpcpp/grpcpp.h>

#include "core/object_model.h"
#include "core/recognition_engine.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"

namespace orbit::server {

// OK when `requested` is unspecified or equals `server`; else INVALID_ARGUMENT naming both.
grpc::Status CheckVariant(v1::DescriptorVariant requested, DescriptorVariant server,
                          std::string_view field);

// A frame as the engines take it. With `cedd`: exactly 144 values, each 0..7. With `image`: the
// image is decoded and its CEDD (of `region` when set, which must lie inside it) computed in
// the server's variant. The azimuth must be finite.
grpc::Status ToQueryFrame(const v1::Frame& frame, DescriptorVariant variant, QueryFrame* out);

// A view as the store keeps it. With `cedd`, the typical distance is taken from the message
// (0, unknown, when absent; else it must be in [0, 1]); with `image`, the server describes the
// image (or its region) as every enrollment path does (core/view_description.h, DescribeView
// with the default seed), so an uploaded image stores what the client library would have sent.
// `thumbnail` receives the view's thumbnail bytes (at most 64 KiB).
grpc::Status ToModelView(const v1::View& view, DescriptorVariant variant, ModelView* out,
                         std::string* thumbnail);

}  // namespace orbit::server
