// The messages of one Models.Enroll stream (proto/orbit/v1/models.proto: a header, then views)
// as the server reads them: each message checked as it arrives, the whole enrollment once the
// client has closed its side. The rules live here, apart from the reactor that moves the
// messages (server/models_service.cc), so that they can be tested and fuzzed without a server
// (fuzz/enroll_stream_fuzzer.cc).
//
// Not thread-safe: one instance per stream, used by one thread at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "core/descriptor/descriptor.h"
#include "orbit/v1/models.pb.h"
#include "server/session_settings.h"
#include "storage/model_store.h"

namespace orbit::server {

class EnrollmentStream {
 public:
  // `variant`: the server's; a header naming another is refused. `max_bytes`: the views together
  // (ServerLimits::max_enrollment_bytes).
  EnrollmentStream(DescriptorVariant variant, std::int64_t max_bytes)
      : variant_(variant), max_bytes_(max_bytes) {}

  // One message, as it arrives. OK when it was taken: the header (the first message, once), or
  // a view (moved out of *request; nothing but its size is checked before ToEnrollment). Else the
  // status that ends the stream: INVALID_ARGUMENT for a second header, a header of another
  // variant, an invalid name or metadata (storage/model_validation.h), a message with neither
  // header nor view, a view before the header; RESOURCE_EXHAUSTED for a view beyond
  // kMaxViewsPerObject or beyond max_bytes of views (naming --max-enrollment-bytes).
  grpc::Status Accept(v1::EnrollRequest* request);

  // After the client closed its side: the enrollment to store, in the server's variant, its
  // metadata "{}" when the header had none, its views read by ToModelViews
  // (server/request_reading.h) within `limits`. INVALID_ARGUMENT without a header or without
  // views; else as ToModelViews. Waits for decode slots when views carry images.
  grpc::Status ToEnrollment(const ServerLimits& limits, Enrollment* out) const;

  // The name the header gave; "" before the header.
  const std::string& name() const { return header_.name(); }

 private:
  const DescriptorVariant variant_;
  const std::int64_t max_bytes_;
  v1::EnrollHeader header_;
  bool have_header_ = false;
  std::vector<v1::View> views_;
  std::int64_t bytes_ = 0;  // ByteSizeLong of the views taken
};

}  // namespace orbit::server
