#include "server/api_conversion.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/cedd.h"
#include "core/typical_distance.h"
#include "storage/model_validation.h"
#include "storage/store_error.h"

namespace orbit::server {
namespace {

grpc::Status Invalid(std::string message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, std::move(message)};
}

grpc::Status ReadCedd(const std::string& bytes, std::string_view field, DescriptorValues* out) {
  if (bytes.size() != static_cast<std::size_t>(kDescriptorSize)) {
    return Invalid(std::string(field) + " has " + std::to_string(bytes.size()) +
                   " bytes; a CEDD descriptor has exactly 144");
  }
  for (int i = 0; i < kDescriptorSize; ++i) {
    const auto value = static_cast<std::uint8_t>(bytes[i]);
    if (value > kDescriptorMaxValue) {
      return Invalid(std::string(field) + " value " + std::to_string(value) + " at index " +
                     std::to_string(i) + " is outside 0..7");
    }
    (*out)[i] = value;
  }
  return grpc::Status::OK;
}

grpc::Status CheckFinite(double value, std::string_view field) {
  if (!std::isfinite(value)) return Invalid(std::string(field) + " must be a finite number");
  return grpc::Status::OK;
}

// Decodes an encoded image and resolves its region of interest.
grpc::Status DecodeImage(const std::string& bytes, const v1::Region& region, bool has_region,
                         cv::Mat* image, std::optional<cv::Rect>* roi) {
  const std::vector<std::uint8_t> buffer(bytes.begin(), bytes.end());
  try {
    *image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image->release();
  }
  if (image->empty()) return Invalid("image is not a PNG, JPEG or other image OpenCV can decode");
  if (image->depth() == CV_16U) image->convertTo(*image, CV_8U, 1.0 / 256);
  if (has_region) {
    const cv::Rect rect(region.x(), region.y(), region.width(), region.height());
    if (rect.width <= 0 || rect.height <= 0 ||
        (rect & cv::Rect(0, 0, image->cols, image->rows)) != rect) {
      return Invalid("region must be non-empty and inside the " + std::to_string(image->cols) +
                     "x" + std::to_string(image->rows) + " image");
    }
    *roi = rect;
  }
  return grpc::Status::OK;
}

}  // namespace

grpc::Status StatusFromException(const std::exception& error) {
  if (dynamic_cast<const std::invalid_argument*>(&error) != nullptr) {
    return Invalid(error.what());
  }
  if (const auto* store = dynamic_cast<const StoreError*>(&error)) {
    switch (store->code()) {
      case StoreError::Code::kNotFound:
        return {grpc::StatusCode::NOT_FOUND, error.what()};
      case StoreError::Code::kAlreadyExists:
        return {grpc::StatusCode::ALREADY_EXISTS, error.what()};
      case StoreError::Code::kFull:
        return {grpc::StatusCode::RESOURCE_EXHAUSTED, error.what()};
      case StoreError::Code::kBusy:
        return {grpc::StatusCode::UNAVAILABLE, error.what()};
      default:
        return {grpc::StatusCode::INTERNAL, error.what()};
    }
  }
  return {grpc::StatusCode::INTERNAL, error.what()};
}

v1::DescriptorVariant ToProto(DescriptorVariant variant) {
  return variant == DescriptorVariant::kCeddLire ? v1::CEDD_LIRE : v1::CEDD_FULL;
}

grpc::Status CheckVariant(v1::DescriptorVariant requested, DescriptorVariant server,
                          std::string_view field) {
  if (requested == v1::DESCRIPTOR_VARIANT_UNSPECIFIED || requested == ToProto(server)) {
    return grpc::Status::OK;
  }
  const std::string asked =
      requested == v1::CEDD_LIRE   ? "cedd-lire"
      : requested == v1::CEDD_FULL ? "cedd-full"
                                   : "unknown (" + std::to_string(requested) + ")";
  return Invalid(std::string(field) + " is " + asked + " but this server's models are " +
                 std::string(VariantName(server)) + "; variants cannot be mixed");
}

grpc::Status ToQueryFrame(const v1::Frame& frame, DescriptorVariant variant, QueryFrame* out) {
  if (auto s = CheckFinite(frame.azimuth_deg(), "frame.azimuth_deg"); !s.ok()) return s;
  if (frame.has_elevation_deg()) {
    if (auto s = CheckFinite(frame.elevation_deg(), "frame.elevation_deg"); !s.ok()) return s;
  }
  out->azimuth = frame.azimuth_deg();
  out->descriptor.variant = variant;
  const bool has_cedd = !frame.cedd().empty(), has_image = !frame.image().empty();
  if (has_cedd == has_image) return Invalid("a frame needs exactly one of cedd and image");
  if (has_cedd) return ReadCedd(frame.cedd(), "frame.cedd", &out->descriptor.values);
  cv::Mat image;
  std::optional<cv::Rect> roi;
  if (auto s = DecodeImage(frame.image(), frame.region(), frame.has_region(), &image, &roi);
      !s.ok()) {
    return s;
  }
  try {
    out->descriptor = ExtractCedd(image, variant, roi);
  } catch (const std::exception& e) {
    return StatusFromException(e);
  }
  return grpc::Status::OK;
}

grpc::Status ToModelView(const v1::View& view, DescriptorVariant variant, std::uint64_t seed,
                         ModelView* out, std::string* thumbnail) {
  if (auto s = CheckFinite(view.azimuth_deg(), "view.azimuth_deg"); !s.ok()) return s;
  out->azimuth = view.azimuth_deg();
  if (view.has_elevation_deg()) {
    if (auto s = CheckFinite(view.elevation_deg(), "view.elevation_deg"); !s.ok()) return s;
    out->elevation = view.elevation_deg();
  }
  if (view.thumbnail().size() > kMaxThumbnailBytes) {
    return Invalid("view.thumbnail is " + std::to_string(view.thumbnail().size()) +
                   " bytes; at most " + std::to_string(kMaxThumbnailBytes));
  }
  *thumbnail = view.thumbnail();
  const bool has_cedd = !view.cedd().empty(), has_image = !view.image().empty();
  if (has_cedd == has_image) return Invalid("a view needs exactly one of cedd and image");
  if (has_cedd) {
    if (view.has_typical_distance()) {
      const double t = view.typical_distance();
      if (!std::isfinite(t) || t < 0 || t > 1) {
        return Invalid("view.typical_distance must be in [0, 1]");
      }
      out->typical_distance = t;
    }
    return ReadCedd(view.cedd(), "view.cedd", &out->descriptor);
  }
  cv::Mat image;
  std::optional<cv::Rect> roi;
  if (auto s = DecodeImage(view.image(), view.region(), view.has_region(), &image, &roi);
      !s.ok()) {
    return s;
  }
  try {
    const cv::Mat region = roi ? image(*roi) : image;
    out->descriptor = ExtractCedd(region, variant).values;
    out->typical_distance = TypicalDistance(region, variant, seed);
  } catch (const std::exception& e) {
    return StatusFromException(e);
  }
  return grpc::Status::OK;
}

v1::ObjectInfo ToObjectInfo(const ObjectSummary& summary) {
  v1::ObjectInfo info;
  info.set_id(summary.id);
  info.set_name(summary.name);
  info.set_variant(ToProto(summary.variant));
  info.set_view_count(summary.view_count);
  info.set_created_at(summary.created_at);
  info.set_updated_at(summary.updated_at);
  info.set_metadata_json(summary.metadata);
  return info;
}

v1::View ToProtoView(const ModelView& view, const std::string& thumbnail) {
  v1::View out;
  out.set_cedd(std::string(view.descriptor.begin(), view.descriptor.end()));
  out.set_azimuth_deg(view.azimuth);
  if (view.elevation) out.set_elevation_deg(*view.elevation);
  out.set_typical_distance(view.typical_distance);
  out.set_thumbnail(thumbnail);
  return out;
}

v1::SessionUpdate ToSessionUpdate(const FrameUpdate& update, const ViewIndexSnapshot& index) {
  v1::SessionUpdate out;
  out.set_frame_index(update.frame_index);
  for (const RankedObject& ranked : update.ranking) {
    v1::Candidate* candidate = out.add_candidates();
    candidate->set_id(ranked.object);
    candidate->set_score(ranked.score);
    if (const IndexedObject* object = index.Find(ranked.object)) {
      candidate->set_name(object->model().name);
    }
  }
  out.set_decision(ToProto(update.decision));
  out.set_move(ToProto(update.move));
  return out;
}

v1::Decision ToProto(Decision decision) {
  switch (decision) {
    case Decision::kAccept:
      return v1::DECISION_ACCEPT;
    case Decision::kUnknown:
      return v1::DECISION_UNKNOWN;
    case Decision::kUndecided:
      return v1::DECISION_UNDECIDED;
  }
  return v1::DECISION_UNSPECIFIED;
}

v1::Move ToProto(SuggestedMove move) {
  switch (move) {
    case SuggestedMove::kNone:
      return v1::MOVE_NONE;
    case SuggestedMove::kLeft:
      return v1::MOVE_LEFT;
    case SuggestedMove::kRight:
      return v1::MOVE_RIGHT;
  }
  return v1::MOVE_UNSPECIFIED;
}

}  // namespace orbit::server
