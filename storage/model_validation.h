// The rules every object model must follow before the store writes it: the store's own line of
// defence, whatever the caller (server, import command, tests) checked before.
//
// Each function throws std::invalid_argument with a message that says what is wrong and where,
// e.g. "view 3: descriptor value 9 at index 17 is outside 0..7".
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/model/object_model.h"
#include "storage/model_store.h"

namespace orbit {

inline constexpr std::size_t kMaxObjectNameLength = 64;
// 1024 views is 0.35 degree steps: far more than any capture needs, small enough that one
// enrollment stays a short transaction.
inline constexpr std::size_t kMaxViewsPerObject = 1024;
inline constexpr std::size_t kMaxThumbnailBytes = 64 * 1024;
inline constexpr std::size_t kMaxMetadataBytes = 16 * 1024;
// Objects and arrays inside one another: far below what the stores' JSON functions accept
// (SQLite's json() and PostgreSQL's jsonb both refuse deep nesting, and a refusal there would
// come back as a store failure), and deeper than any metadata a person writes.
inline constexpr int kMaxMetadataDepth = 32;

// A name is 1..kMaxObjectNameLength ASCII letters, digits, '_', '-' and '.', starting with a
// letter or a digit: safe in file names, URLs, shell commands and `orbit list` columns.
void ValidateObjectName(std::string_view name);

// A view is valid when its descriptor values are in 0..kDescriptorMaxValue, its azimuth is finite
// (the store keeps NormaliseAzimuth of it, core/base/angles.h: in [0, 360)),
// its elevation (if any) is finite and in [-90, 90], and its typical distance is in [0, 1]
// (docs/design.md#typical-distance). `position` (the view's index) prefixes the message.
void ValidateView(const ModelView& view, std::size_t position);

// The views of one write: 1..kMaxViewsPerObject valid views, and `thumbnails` empty or one per
// view, each at most kMaxThumbnailBytes.
void ValidateViews(const std::vector<ModelView>& views, const std::vector<std::string>& thumbnails);

// Metadata is the text of one JSON object, at most kMaxMetadataBytes, nesting objects and arrays
// at most kMaxMetadataDepth deep.
void ValidateMetadata(std::string_view metadata);

// A whole object as another store gave it (ModelStore::RestoreFrom): its name, views, thumbnails
// and metadata by the rules above.
void ValidateStoredObject(const StoredObject& object);

}  // namespace orbit
