#include "storage/model_validation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace orbit {
namespace {

bool IsAsciiAlnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

}  // namespace

void ValidateObjectName(std::string_view name) {
  if (name.empty()) throw std::invalid_argument("object name is empty");
  if (name.size() > kMaxObjectNameLength) {
    throw std::invalid_argument("object name has " + std::to_string(name.size()) +
                                " characters, more than the limit of " +
                                std::to_string(kMaxObjectNameLength));
  }
  if (!IsAsciiAlnum(name[0])) {
    throw std::invalid_argument("object name \"" + std::string(name) +
                                "\" must start with a letter or a digit");
  }
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (!IsAsciiAlnum(c) && c != '_' && c != '-' && c != '.') {
      throw std::invalid_argument(
          "object name \"" + std::string(name) + "\" has a character not allowed at position " +
          std::to_string(i) + " (allowed: ASCII letters, digits, '_', '-', '.')");
    }
  }
}

void ValidateView(const ModelView& view, std::size_t position) {
  const std::string where = "view " + std::to_string(position) + ": ";
  try {
    ValidateDescriptorValues(view.descriptor);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + e.what());
  }
  if (!std::isfinite(view.azimuth)) {
    throw std::invalid_argument(where + "azimuth " + std::to_string(view.azimuth) +
                                " is not a finite number");
  }
  if (view.elevation &&
      (!std::isfinite(*view.elevation) || *view.elevation < -90 || *view.elevation > 90)) {
    throw std::invalid_argument(where + "elevation " + std::to_string(*view.elevation) +
                                " is outside [-90, 90] degrees");
  }
  if (!(view.typical_distance >= 0 && view.typical_distance <= 1)) {
    throw std::invalid_argument(where + "typical distance " +
                                std::to_string(view.typical_distance) +
                                " is outside [0, 1] (a Tanimoto distance)");
  }
}

void ValidateViews(const std::vector<ModelView>& views,
                   const std::vector<std::string>& thumbnails) {
  if (views.empty()) throw std::invalid_argument("no views: an object needs at least one view");
  if (views.size() > kMaxViewsPerObject) {
    throw std::invalid_argument(std::to_string(views.size()) + " views, more than the limit of " +
                                std::to_string(kMaxViewsPerObject) + " per object");
  }
  if (!thumbnails.empty() && thumbnails.size() != views.size()) {
    throw std::invalid_argument(std::to_string(thumbnails.size()) + " thumbnails for " +
                                std::to_string(views.size()) + " views: give none or one per view");
  }
  for (std::size_t i = 0; i < views.size(); ++i) ValidateView(views[i], i);
  for (std::size_t i = 0; i < thumbnails.size(); ++i) {
    if (thumbnails[i].size() > kMaxThumbnailBytes) {
      throw std::invalid_argument(
          "view " + std::to_string(i) + ": thumbnail of " + std::to_string(thumbnails[i].size()) +
          " bytes is larger than the limit of " + std::to_string(kMaxThumbnailBytes));
    }
  }
}

namespace {

// The deepest nesting of objects and arrays in `json`, brackets inside strings not counted. Read
// before parsing, so that no parser or store is handed deeper text.
int NestingDepth(std::string_view json) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : json) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

void ValidateMetadata(std::string_view metadata) {
  if (metadata.size() > kMaxMetadataBytes) {
    throw std::invalid_argument("metadata of " + std::to_string(metadata.size()) +
                                " bytes is larger than the limit of " +
                                std::to_string(kMaxMetadataBytes));
  }
  if (const int depth = NestingDepth(metadata); depth > kMaxMetadataDepth) {
    throw std::invalid_argument("metadata nests objects and arrays " + std::to_string(depth) +
                                " deep, more than the limit of " +
                                std::to_string(kMaxMetadataDepth));
  }
  const nlohmann::json parsed =
      nlohmann::json::parse(metadata, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) throw std::invalid_argument("metadata is not valid JSON");
  if (!parsed.is_object()) throw std::invalid_argument("metadata must be a JSON object ({...})");
}

void ValidateStoredObject(const StoredObject& object) {
  ValidateObjectName(object.summary.name);
  ValidateViews(object.views, object.thumbnails);
  ValidateMetadata(object.summary.metadata);
}

}  // namespace orbit
