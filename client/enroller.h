// Enroller: turns images of a new object, each with the azimuth it was taken at, into an
// enrolled object on the server (Models.Enroll, proto/orbit/v1/models.proto).
//
// Everything heavy happens on the device: each view's CEDD (in the server's descriptor variant)
// and its typical distance Ttyp, described exactly as the server, `orbit import` and the
// evaluation describe a view (core/descriptor/view_description.h, DescribeView;
// docs/design.md#typical-distance), so the server receives 144 bytes and one number per view
// and never an image. The object is committed atomically when the stream ends: on any error
// nothing is stored.
//
// Errors: RpcError with the server's status (ALREADY_EXISTS for a name in use,
// INVALID_ARGUMENT for a bad name or view, PERMISSION_DENIED without the `admin` role, ...);
// std::invalid_argument for an empty image list, an empty image or a region outside its image.
// Thread safety: one Enroller per thread (it caches the server's variant without locking).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "client/capture_reader.h"
#include "client/capture_views.h"
#include "client/connection.h"
#include "client/enrollment_image.h"
#include "core/descriptor/descriptor.h"
#include "core/descriptor/view_description.h"
#include "orbit/v1/models.grpc.pb.h"

namespace orbit {

// The view the server stores for `image`: DescribeView of the region (or whole image), with
// `base_seed` in the seed rule of core/descriptor/view_description.h, and the image's azimuth and
// elevation. Throws std::invalid_argument for an empty image or a region outside it, and as
// DescribeView.
v1::View ComputeView(const EnrollmentImage& image, DescriptorVariant variant,
                     std::uint64_t base_seed = kDefaultViewNoiseSeed);

struct EnrollerOptions {
  // Base of the noise seed rule (core/descriptor/view_description.h); the default stores what the
  // server would compute from the same images.
  std::uint64_t seed = kDefaultViewNoiseSeed;
  unsigned threads = 1;  // threads computing the views
};

class Enroller {
 public:
  // `connection` must outlive the enroller.
  explicit Enroller(const Connection& connection, EnrollerOptions options = {});

  // Computes the views of `images` (view f from images[f]) in the server's variant, on
  // options.threads threads.
  std::vector<v1::View> ComputeViews(const std::vector<EnrollmentImage>& images);

  // Computes the views and enrolls them as object `name`; returns the stored object.
  v1::ObjectInfo Enroll(const std::string& name, const std::vector<EnrollmentImage>& images,
                        const std::string& metadata_json = "{}");

  // Enrolls object `name` from a walk around it (docs/capture.md): chooses the views
  // (SelectCaptureViews: the sharpest usable frame of each azimuth step, on the tracked
  // region), computes them and enrolls them in one atomic Enroll. Returns the stored object and
  // what the capture gave. Throws std::invalid_argument, before anything is sent, when no frame
  // is usable, and as SelectCaptureViews and Enroll.
  struct VideoEnrollment {
    v1::ObjectInfo object;
    CaptureViewSelection selection;
  };
  VideoEnrollment FromVideo(const std::string& name, CaptureReader& capture,
                            const CaptureViewOptions& options = {},
                            const std::string& metadata_json = "{}");

  // Enrolls views computed already (by ComputeViews, or descriptors from elsewhere).
  v1::ObjectInfo EnrollViews(const std::string& name, const std::vector<v1::View>& views,
                             const std::string& metadata_json = "{}");

  // The server's descriptor variant, asked once (ServerInfo) and cached.
  DescriptorVariant variant();

 private:
  const Connection& connection_;
  const EnrollerOptions options_;
  std::unique_ptr<v1::Models::Stub> stub_;
  std::optional<DescriptorVariant> variant_;
};

}  // namespace orbit
