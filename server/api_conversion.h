// Between the wire types of proto/orbit/v1 and the types of core/ and storage/, with the checks
// SPEC.md's "Service behaviour" asks for. Every refusal is INVALID_ARGUMENT with a message that
// names the field and says what is wrong. Pure functions, thread-safe.
#pragma once

#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include <grpcpp/grpcpp.h>

#include "core/object_model.h"
#include "core/recognition_engine.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"
#include "storage/model_store.h"

namespace orbit::server {

// The status for an exception thrown by core/ or storage/: std::invalid_argument ->
// INVALID_ARGUMENT; StoreError by code (not found -> NOT_FOUND, already exists ->
// ALREADY_EXISTS, full -> RESOURCE_EXHAUSTED, busy -> UNAVAILABLE, else INTERNAL); anything else
// INTERNAL. The message is the exception's.
grpc::Status StatusFromException(const std::exception& error);

v1::DescriptorVariant ToProto(DescriptorVariant variant);

// OK when `requested` is unspecified or equals `server`; else INVALID_ARGUMENT naming both.
grpc::Status CheckVariant(v1::DescriptorVariant requested, DescriptorVariant server,
                          std::string_view field);

// A frame as the engines take it. With `cedd`: exactly 144 values, each 0..7. With `image`: the
// image is decoded and its CEDD (of `region` when set, which must lie inside it) computed in
// the server's variant. The azimuth must be finite.
grpc::Status ToQueryFrame(const v1::Frame& frame, DescriptorVariant variant, QueryFrame* out);

// A view as the store keeps it. With `cedd`, the typical distance is taken from the message
// (0, unknown, when absent; else it must be in [0, 1]); with `image`, the server computes the
// descriptor and the typical distance (core/typical_distance.h, with `seed`).
// `thumbnail` receives the view's thumbnail bytes (at most 64 KiB).
grpc::Status ToModelView(const v1::View& view, DescriptorVariant variant, std::uint64_t seed,
                         ModelView* out, std::string* thumbnail);

v1::ObjectInfo ToObjectInfo(const ObjectSummary& summary);
v1::View ToProtoView(const ModelView& view, const std::string& thumbnail);

// An engine's update as the wire carries it, with each candidate's name from `index` (the
// snapshot the update was computed on).
v1::SessionUpdate ToSessionUpdate(const FrameUpdate& update, const ViewIndexSnapshot& index);

v1::Decision ToProto(Decision decision);
v1::Move ToProto(SuggestedMove move);

}  // namespace orbit::server
