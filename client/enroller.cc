#include "client/enroller.h"

#include <stdexcept>

#include "api/conversion.h"
#include "client/models_client.h"
#include "client/rpc_error.h"
#include "core/base/parallel_for.h"

namespace orbit {

v1::View ComputeView(const EnrollmentImage& image, DescriptorVariant variant,
                     std::uint64_t base_seed) {
  if (image.image.empty()) throw std::invalid_argument("empty enrollment image");
  const cv::Rect whole(0, 0, image.image.cols, image.image.rows);
  const cv::Rect region = image.region.value_or(whole);
  if (region.width <= 0 || region.height <= 0 || (region & whole) != region) {
    throw std::invalid_argument("enrollment region is empty or not inside its image");
  }
  // The distortions are applied to the region alone, as a device would crop the object first.
  const ViewDescription described = DescribeView(image.image(region), variant, base_seed);
  ModelView view;
  view.descriptor = described.descriptor;
  view.azimuth = image.azimuth_deg;
  view.elevation = image.elevation_deg;
  view.typical_distance = described.typical_distance;
  return ToProtoView(view, variant);
}

Enroller::Enroller(const Connection& connection, EnrollerOptions options)
    : connection_(connection), options_(options), stub_(v1::Models::NewStub(connection.channel())) {
  if (options_.threads == 0) throw std::invalid_argument("Enroller needs at least one thread");
}

DescriptorVariant Enroller::variant() {
  if (!variant_) variant_ = FromProtoVariant(ModelsClient(connection_).ServerInfo().variant());
  return *variant_;
}

std::vector<v1::View> Enroller::ComputeViews(const std::vector<EnrollmentImage>& images) {
  const DescriptorVariant descriptor_variant = variant();
  std::vector<v1::View> views(images.size());
  ParallelFor(images.size(), static_cast<int>(options_.threads), [&](std::size_t f) {
    views[f] = ComputeView(images[f], descriptor_variant, options_.seed);
  });
  return views;
}

v1::ObjectInfo Enroller::Enroll(const std::string& name, const std::vector<EnrollmentImage>& images,
                                const std::string& metadata_json) {
  if (images.empty()) throw std::invalid_argument("no images to enroll for " + name);
  return EnrollViews(name, ComputeViews(images), metadata_json);
}

Enroller::VideoEnrollment Enroller::FromVideo(const std::string& name, CaptureReader& capture,
                                              const CaptureViewOptions& options,
                                              const std::string& metadata_json) {
  VideoEnrollment enrollment;
  enrollment.selection = SelectCaptureViews(capture, options);
  if (enrollment.selection.views.empty()) {
    throw std::invalid_argument("no usable frame in " + capture.video_path() + " (" +
                                std::to_string(enrollment.selection.frames_read) + " read, " +
                                std::to_string(enrollment.selection.frames_lost) + " lost, " +
                                std::to_string(enrollment.selection.frames_unusable) +
                                " too blurred or noisy): nothing to enroll for " + name);
  }
  std::vector<EnrollmentImage> images;
  for (const CaptureView& view : enrollment.selection.views) images.push_back(view.image);
  enrollment.object = Enroll(name, images, metadata_json);
  return enrollment;
}

v1::ObjectInfo Enroller::EnrollViews(const std::string& name, const std::vector<v1::View>& views,
                                     const std::string& metadata_json) {
  if (views.empty()) throw std::invalid_argument("no views to enroll for " + name);
  grpc::ClientContext context;
  connection_.PrepareUnaryCall(context);
  v1::ObjectInfo object;
  auto stream = stub_->Enroll(&context, &object);

  v1::EnrollRequest request;
  v1::EnrollHeader* header = request.mutable_header();
  header->set_name(name);
  header->set_variant(ToProtoVariant(variant()));
  header->set_metadata_json(metadata_json);
  // A failed write means the server has ended the call already; its status says why.
  bool writing = stream->Write(request);
  for (std::size_t f = 0; writing && f < views.size(); ++f) {
    *request.mutable_view() = views[f];
    writing = stream->Write(request);
  }
  if (writing) stream->WritesDone();
  ThrowIfError("Enroll", stream->Finish());
  return object;
}

}  // namespace orbit
