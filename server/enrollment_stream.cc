#include "server/enrollment_stream.h"

#include <string>
#include <utility>

#include "server/error_status.h"
#include "server/request_reading.h"
#include "storage/model_validation.h"

namespace orbit::server {

grpc::Status EnrollmentStream::Accept(v1::EnrollRequest* request) {
  if (request->kind_case() == v1::EnrollRequest::kHeader) {
    if (have_header_) return InvalidArgument("the header may be sent only once");
    const v1::EnrollHeader& header = request->header();
    if (auto s = CheckVariant(header.variant(), variant_, "header.variant"); !s.ok()) return s;
    try {
      ValidateObjectName(header.name());
      ValidateMetadata(header.metadata_json().empty() ? "{}" : header.metadata_json());
    } catch (const std::exception& e) {
      return StatusFromException(e);
    }
    header_ = header;
    have_header_ = true;
    return grpc::Status::OK;
  }
  if (request->kind_case() != v1::EnrollRequest::kView) {
    return InvalidArgument("empty request: set header or view");
  }
  if (!have_header_) return InvalidArgument("the first message must be the header");
  if (views_.size() >= kMaxViewsPerObject) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "more than " + std::to_string(kMaxViewsPerObject) + " views for one object"};
  }
  bytes_ += static_cast<std::int64_t>(request->view().ByteSizeLong());
  if (bytes_ > max_bytes_) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "the enrollment's views are more than " +
                                                      std::to_string(max_bytes_) +
                                                      " bytes (--max-enrollment-bytes)"};
  }
  views_.push_back(std::move(*request->mutable_view()));
  return grpc::Status::OK;
}

grpc::Status EnrollmentStream::ToEnrollment(const ServerLimits& limits, Enrollment* out) const {
  if (!have_header_) return InvalidArgument("no header: nothing to enroll");
  if (views_.empty()) return InvalidArgument("no views: an object needs at least one");
  Enrollment enrollment;
  enrollment.name = header_.name();
  enrollment.variant = variant_;
  enrollment.metadata = header_.metadata_json().empty() ? "{}" : header_.metadata_json();
  if (grpc::Status s =
          ToModelViews(views_, variant_, limits, &enrollment.views, &enrollment.thumbnails);
      !s.ok()) {
    return s;
  }
  *out = std::move(enrollment);
  return grpc::Status::OK;
}

}  // namespace orbit::server
