// Fuzz target: the messages of one Models.Enroll stream, checked as the server checks them
// (server/enrollment_stream.h, which server/models_service.cc's reactor drives): each message
// as it arrives, then the whole enrollment when the client closes its side (views read by
// ToModelViews: descriptors, typical distances, thumbnails, images decoded within the budget
// and described), then the rules the model store applies before it writes
// (storage/model_validation.h).
//
// Input: a stream of length-delimited orbit.v1.EnrollRequest messages (each a varint length,
// then the message; protobuf's SerializeDelimitedToOstream), read until the bytes end or a
// message does not parse. The seeds (corpus/enroll_stream/) hold a header with views sent as
// descriptors and as a small PNG and JPEG, and streams out of order.
//
// Checked beyond "no crash": an enrollment the stream accepts has the header's name, the
// server's variant, one view per view message, one thumbnail per view or none, and passes the
// store's name, metadata and view rules, but for elevations outside [-90, 90], which only the
// store refuses.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "orbit/v1/models.pb.h"
#include "server/enrollment_stream.h"
#include "storage/model_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  constexpr auto kVariant = DescriptorVariant::kCeddLire;
  // Describing an image (CEDD, then its blurred and noisy copies and theirs) under the fuzzer's
  // instrumentation costs many times what it costs in a release build (docs/results/fuzz.md,
  // "What was found"), so on a busy machine streams of a few 512 x 512 images ran past the
  // timeout. So images here are smaller than FuzzLimits' and a stream's images are described
  // only up to kMaxDescribedImages: the checks a larger stream meets are the same ones, and the
  // server's budget for many large images is image_budget's.
  constexpr int kMaxDescribedImages = 16;
  static const server::ServerLimits limits = [] {
    server::ServerLimits l = fuzz::FuzzLimits();
    l.max_image_pixels = 128 * 128;
    return l;
  }();

  fuzz::SilenceProtobufLogs();
  std::vector<v1::EnrollRequest> requests =
      fuzz::ReadDelimitedMessages<v1::EnrollRequest>(data, size);
  server::EnrollmentStream stream(kVariant, server::ServerLimits().max_enrollment_bytes);
  std::string name;
  std::size_t view_messages = 0;
  int images = 0;
  for (const v1::EnrollRequest& request : requests) {
    if (request.has_view() && !request.view().image().empty()) ++images;
  }
  if (images > kMaxDescribedImages) return 0;
  for (v1::EnrollRequest& request : requests) {
    const bool is_view = request.has_view();
    if (request.has_header()) name = request.header().name();
    if (!stream.Accept(&request).ok()) return 0;  // the stream ends here
    if (is_view) ++view_messages;
  }
  Enrollment enrollment;
  if (!stream.ToEnrollment(limits, &enrollment).ok()) return 0;
  ORBIT_FUZZ_CHECK(enrollment.name == name);
  ORBIT_FUZZ_CHECK(enrollment.variant == kVariant);
  ORBIT_FUZZ_CHECK(enrollment.views.size() == view_messages);
  ORBIT_FUZZ_CHECK(enrollment.thumbnails.empty() ||
                   enrollment.thumbnails.size() == enrollment.views.size());
  bool elevation_in_range = true;
  for (const ModelView& view : enrollment.views) {
    if (view.elevation && std::abs(*view.elevation) > 90) elevation_in_range = false;
  }
  try {
    ValidateObjectName(enrollment.name);
    ValidateMetadata(enrollment.metadata);
    ValidateViews(enrollment.views, enrollment.thumbnails);
  } catch (const std::exception& e) {
    if (elevation_in_range) {
      std::fprintf(stderr, "the store refuses what the server accepted: %s\n", e.what());
      ORBIT_FUZZ_CHECK(false);
    }
  }
  return 0;
}
