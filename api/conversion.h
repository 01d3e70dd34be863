// Between the types of core/ a device sends (descriptor variants, descriptors, views) and the
// messages of proto/orbit/v1, both ways where both are needed: the one conversion unit the
// client library and the server share, so that the two ends of a call cannot drift apart (they
// once defaulted an unknown variant differently). What the engines answer is converted in
// api/engines/conversion.h, which a device does not link.
//
// Refusals are std::invalid_argument with a message naming the field; the server turns them
// into INVALID_ARGUMENT. Pure functions, thread-safe.
#pragma once

#include <string>
#include <string_view>

#include "core/descriptor/descriptor.h"
#include "core/model/object_model.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"

namespace orbit {

// CEDD_LIRE <-> kCeddLire, CEDD_FULL <-> kCeddFull. FromProtoVariant throws
// std::invalid_argument for DESCRIPTOR_VARIANT_UNSPECIFIED or a value this build does not know.
v1::DescriptorVariant ToProtoVariant(DescriptorVariant variant);
DescriptorVariant FromProtoVariant(v1::DescriptorVariant variant);

// "cedd-lire", "cedd-full", "unspecified" or "unknown (N)": for messages.
std::string ProtoVariantName(v1::DescriptorVariant variant);

// The descriptor a message carries in `variant`: its `cedd` field, exactly 144 bytes, and its
// `appearance` field, exactly DescriptorLength(variant) - 144 bytes (none in the CEDD variants),
// each 0..7 (core/descriptor/descriptor.h's check). Throws std::invalid_argument naming the
// field of `message`, e.g. "frame.cedd value 9 at index 17 is outside 0..7" or
// "frame.appearance has 0 values, expected 336 for cedd-hsv-hog".
DescriptorValues DescriptorFromWire(const std::string& cedd, const std::string& appearance,
                                    DescriptorVariant variant, std::string_view message);

// The inverse: `values` of `variant` split into a message's `cedd` and `appearance` fields.
void SetWireDescriptor(const DescriptorValues& values, DescriptorVariant variant, std::string* cedd,
                       std::string* appearance);

// A stored view of an object of `variant` on the wire: its descriptor, azimuth, elevation when
// known, typical distance and `thumbnail` (empty: none).
v1::View ToProtoView(const ModelView& view, DescriptorVariant variant,
                     const std::string& thumbnail = "");

}  // namespace orbit
