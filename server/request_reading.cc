#include "server/request_reading.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "api/conversion.h"
#include "core/descriptor/blur_estimate.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/noise_estimate.h"
#include "core/descriptor/query_frame.h"
#include "core/descriptor/view_description.h"
#include "server/error_status.h"
#include "server/image_decoding.h"
#include "storage/model_validation.h"

namespace orbit::server {
namespace {

// The descriptor of a frame's or view's `cedd` and `appearance` fields.
template <typename Message>
grpc::Status ReadDescriptor(const Message& message, DescriptorVariant variant,
                            std::string_view name, DescriptorValues* out) {
  try {
    *out = DescriptorFromWire(message.cedd(), message.appearance(), variant, name);
  } catch (const std::invalid_argument& e) {
    return InvalidArgument(e.what());
  }
  return grpc::Status::OK;
}

grpc::Status CheckFinite(double value, std::string_view field) {
  if (!std::isfinite(value))
    return InvalidArgument(std::string(field) + " must be a finite number");
  return grpc::Status::OK;
}

// An uploaded image, decoded, and its region of interest.
struct RequestImage {
  DecodedImage decoded;
  std::optional<cv::Rect> roi;  // the request's region, when it has one
};

// Decodes the encoded image `bytes` (the request's `field`) within limits.max_image_pixels
// (server/image_decoding.h) and resolves its region of interest.
grpc::Status ReadRequestImage(const std::string& bytes, std::string_view field,
                              const ServerLimits& limits, const v1::Region& region, bool has_region,
                              RequestImage* out) {
  if (auto s = DecodeImage(bytes, field, limits.max_image_pixels, &out->decoded); !s.ok()) {
    return s;
  }
  const cv::Mat& image = out->decoded.pixels;
  if (has_region) {
    const cv::Rect rect(region.x(), region.y(), region.width(), region.height());
    if (rect.width <= 0 || rect.height <= 0 ||
        (rect & cv::Rect(0, 0, image.cols, image.rows)) != rect) {
      return InvalidArgument("region must be non-empty and inside the " +
                             std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                             " image");
    }
    out->roi = rect;
  }
  return grpc::Status::OK;
}

}  // namespace

grpc::Status CheckVariant(v1::DescriptorVariant requested, DescriptorVariant server,
                          std::string_view field) {
  if (requested == v1::DESCRIPTOR_VARIANT_UNSPECIFIED || requested == ToProtoVariant(server)) {
    return grpc::Status::OK;
  }
  return InvalidArgument(std::string(field) + " is " + ProtoVariantName(requested) +
                         " but this server's models are " + std::string(VariantName(server)) +
                         "; variants cannot be mixed");
}

grpc::Status ToQueryFrame(const v1::Frame& frame, DescriptorVariant variant,
                          const ServerLimits& limits, QueryFrame* out) {
  out->azimuth =
      frame.has_azimuth_deg() ? std::optional<double>(frame.azimuth_deg()) : std::nullopt;
  out->noise_sigma.reset();
  out->blur.reset();
  if (frame.has_quality()) {
    out->noise_sigma = frame.quality().noise_sigma();
    out->blur = frame.quality().blur();
  }
  out->descriptor = {};
  try {
    ValidateQueryFrame(*out, {.descriptor = "frame.cedd",
                              .azimuth = "frame.azimuth_deg",
                              .noise_sigma = "frame.quality.noise_sigma",
                              .blur = "frame.quality.blur"});
  } catch (const std::invalid_argument& e) {
    return InvalidArgument(e.what());
  }
  if (frame.has_elevation_deg()) {
    if (auto s = CheckFinite(frame.elevation_deg(), "frame.elevation_deg"); !s.ok()) return s;
  }
  out->descriptor.variant = variant;
  const bool has_cedd = !frame.cedd().empty(), has_image = !frame.image().empty();
  if (has_cedd == has_image) return InvalidArgument("a frame needs exactly one of cedd and image");
  if (has_cedd) return ReadDescriptor(frame, variant, "frame", &out->descriptor.values);
  RequestImage image;
  if (auto s = ReadRequestImage(frame.image(), "frame.image", limits, frame.region(),
                                frame.has_region(), &image);
      !s.ok()) {
    return s;
  }
  try {
    out->descriptor = ExtractCedd(image.decoded.pixels, variant, image.roi);
    // A device that sends pixels is measured here, as the client library measures its own.
    if (!frame.has_quality()) {
      const cv::Mat region = image.roi ? image.decoded.pixels(*image.roi) : image.decoded.pixels;
      out->noise_sigma = EstimateNoiseSigma(region);
      out->blur = EstimateBlur(region);
    }
  } catch (const std::exception& e) {
    return StatusFromException(e);
  }
  return grpc::Status::OK;
}

grpc::Status ToModelView(const v1::View& view, DescriptorVariant variant,
                         const ServerLimits& limits, ModelView* out, std::string* thumbnail) {
  if (auto s = CheckFinite(view.azimuth_deg(), "view.azimuth_deg"); !s.ok()) return s;
  out->azimuth = view.azimuth_deg();
  if (view.has_elevation_deg()) {
    if (auto s = CheckFinite(view.elevation_deg(), "view.elevation_deg"); !s.ok()) return s;
    out->elevation = view.elevation_deg();
  }
  if (view.thumbnail().size() > kMaxThumbnailBytes) {
    return InvalidArgument("view.thumbnail is " + std::to_string(view.thumbnail().size()) +
                           " bytes; at most " + std::to_string(kMaxThumbnailBytes));
  }
  *thumbnail = view.thumbnail();
  const bool has_cedd = !view.cedd().empty(), has_image = !view.image().empty();
  if (has_cedd == has_image) return InvalidArgument("a view needs exactly one of cedd and image");
  if (has_cedd) {
    if (view.has_typical_distance()) {
      const double t = view.typical_distance();
      if (!std::isfinite(t) || t < 0 || t > 1) {
        return InvalidArgument("view.typical_distance must be in [0, 1]");
      }
      out->typical_distance = t;
    }
    return ReadDescriptor(view, variant, "view", &out->descriptor);
  }
  RequestImage image;
  if (auto s = ReadRequestImage(view.image(), "view.image", limits, view.region(),
                                view.has_region(), &image);
      !s.ok()) {
    return s;
  }
  try {
    const cv::Mat& pixels = image.decoded.pixels;
    const ViewDescription described =
        DescribeView(image.roi ? pixels(*image.roi) : pixels, variant);
    out->descriptor = described.descriptor;
    out->typical_distance = described.typical_distance;
  } catch (const std::exception& e) {
    return StatusFromException(e);
  }
  return grpc::Status::OK;
}

grpc::Status ToModelViews(const std::vector<v1::View>& wire, DescriptorVariant variant,
                          const ServerLimits& limits, std::vector<ModelView>* views,
                          std::vector<std::string>* thumbnails) {
  bool any_thumbnail = false;
  for (std::size_t i = 0; i < wire.size(); ++i) {
    ModelView view;
    std::string thumbnail;
    if (grpc::Status s = ToModelView(wire[i], variant, limits, &view, &thumbnail); !s.ok()) {
      return grpc::Status(s.error_code(), "view " + std::to_string(i) + ": " + s.error_message());
    }
    any_thumbnail = any_thumbnail || !thumbnail.empty();
    views->push_back(view);
    thumbnails->push_back(std::move(thumbnail));
  }
  if (!any_thumbnail) thumbnails->clear();
  return grpc::Status::OK;
}

}  // namespace orbit::server
