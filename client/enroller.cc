#include "client/enroller.h"

#include <stdexcept>
#include <thread>

#include "client/models_client.h"
#include "client/rpc_error.h"
#include "core/cedd.h"
#include "core/typical_distance.h"

namespace orbit {

v1::View ComputeView(const EnrollmentImage& image, DescriptorVariant variant, std::uint64_t seed) {
  if (image.image.empty()) throw std::invalid_argument("empty enrollment image");
  const cv::Rect whole(0, 0, image.image.cols, image.image.rows);
  const cv::Rect region = image.region.value_or(whole);
  if (region.width <= 0 || region.height <= 0 || (region & whole) != region) {
    throw std::invalid_argument("enrollment region is empty or not inside its image");
  }
  // The distortions are applied to the region alone, as a device would crop the object first.
  const cv::Mat pixels = image.image(region);
  const DescriptorValues values = ExtractCedd(pixels, variant).values;
  std::array<DescriptorValues, kTypicalDistortionCount> copies;
  const auto distorted = TypicalDistortions(pixels, seed);
  for (int i = 0; i < kTypicalDistortionCount; ++i) {
    copies[i] = ExtractCedd(distorted[i], variant).values;
  }

  v1::View view;
  view.set_cedd(values.data(), values.size());
  view.set_azimuth_deg(image.azimuth_deg);
  if (image.elevation_deg) view.set_elevation_deg(*image.elevation_deg);
  view.set_typical_distance(TypicalDistance(values, copies));
  return view;
}

Enroller::Enroller(const Connection& connection, EnrollerOptions options)
    : connection_(connection),
      options_(options),
      stub_(v1::Models::NewStub(connection.channel())) {
  if (options_.threads == 0) throw std::invalid_argument("Enroller needs at least one thread");
}

DescriptorVariant Enroller::variant() {
  if (!variant_) variant_ = FromProtoVariant(ModelsClient(connection_).ServerInfo().variant());
  return *variant_;
}

std::vector<v1::View> Enroller::ComputeViews(const std::vector<EnrollmentImage>& images) {
  const DescriptorVariant descriptor_variant = variant();
  std::vector<v1::View> views(images.size());
  const unsigned threads = static_cast<unsigned>(
      std::min<std::size_t>(options_.threads, std::max<std::size_t>(1, images.size())));
  std::vector<std::exception_ptr> errors(threads);
  auto work = [&](unsigned worker) {
    try {
      for (std::size_t f = worker; f < images.size(); f += threads) {
        views[f] = ComputeView(images[f], descriptor_variant, options_.seed + f);
      }
    } catch (...) {
      errors[worker] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return views;
}

v1::ObjectInfo Enroller::Enroll(const std::string& name, const std::vector<EnrollmentImage>& images,
                                const std::string& metadata_json) {
  if (images.empty()) throw std::invalid_argument("no images to enroll for " + name);
  return EnrollViews(name, ComputeViews(images), metadata_json);
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
