// The rules of one Enroll stream (server/enrollment_stream.h), without a server: what each
// message may be, in which order, and what the enrollment holds once the client closes its side.
#include "server/enrollment_stream.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/descriptor/view_description.h"
#include "storage/model_validation.h"

namespace orbit::server {
namespace {

constexpr auto kLire = DescriptorVariant::kCeddLire;
const ServerLimits kLimits;
const std::int64_t kMaxBytes = kLimits.max_enrollment_bytes;

v1::EnrollRequest Header(const std::string& name, const std::string& metadata = "") {
  v1::EnrollRequest request;
  request.mutable_header()->set_name(name);
  request.mutable_header()->set_metadata_json(metadata);
  return request;
}

v1::EnrollRequest View(std::uint8_t fill, double azimuth) {
  v1::EnrollRequest request;
  request.mutable_view()->set_cedd(std::string(kCeddSize, static_cast<char>(fill)));
  request.mutable_view()->set_azimuth_deg(azimuth);
  return request;
}

void ExpectStatus(const grpc::Status& status, grpc::StatusCode code, const std::string& message) {
  EXPECT_EQ(status.error_code(), code) << status.error_message();
  EXPECT_EQ(status.error_message(), message);
}

TEST(EnrollmentStreamTest, AHeaderThenViewsMakeTheEnrollment) {
  EnrollmentStream stream(kLire, kMaxBytes);
  v1::EnrollRequest header = Header("mug");
  v1::EnrollRequest first = View(1, 10), second = View(2, 370);
  second.mutable_view()->set_typical_distance(0.25);
  ASSERT_TRUE(stream.Accept(&header).ok());
  ASSERT_TRUE(stream.Accept(&first).ok());
  ASSERT_TRUE(stream.Accept(&second).ok());
  Enrollment enrollment;
  ASSERT_TRUE(stream.ToEnrollment(kLimits, &enrollment).ok());
  EXPECT_EQ(enrollment.name, "mug");
  EXPECT_EQ(enrollment.variant, kLire);
  EXPECT_EQ(enrollment.metadata, "{}");  // none given
  ASSERT_EQ(enrollment.views.size(), 2u);
  EXPECT_EQ(enrollment.views[0].descriptor[143], 1);
  EXPECT_EQ(enrollment.views[0].azimuth, 10);
  EXPECT_EQ(enrollment.views[0].typical_distance, 0);  // unknown
  EXPECT_EQ(enrollment.views[1].azimuth, 370);         // the store normalises it
  EXPECT_EQ(enrollment.views[1].typical_distance, 0.25);
  EXPECT_TRUE(enrollment.thumbnails.empty());  // no view has one
}

TEST(EnrollmentStreamTest, AViewSentAsAnImageIsDescribedAndThumbnailsAreKeptPerView) {
  cv::Mat image(24, 32, CV_8UC3);
  cv::randu(image, 0, 256);
  std::vector<std::uint8_t> png;
  cv::imencode(".png", image, png);
  EnrollmentStream stream(kLire, kMaxBytes);
  v1::EnrollRequest header = Header("box", R"({"shelf": 4})");
  v1::EnrollRequest described = View(3, 0);
  v1::EnrollRequest uploaded;
  uploaded.mutable_view()->set_image(std::string(png.begin(), png.end()));
  uploaded.mutable_view()->set_thumbnail("tiny");
  ASSERT_TRUE(stream.Accept(&header).ok());
  ASSERT_TRUE(stream.Accept(&described).ok());
  ASSERT_TRUE(stream.Accept(&uploaded).ok());
  Enrollment enrollment;
  ASSERT_TRUE(stream.ToEnrollment(kLimits, &enrollment).ok());
  EXPECT_EQ(enrollment.metadata, R"({"shelf": 4})");
  EXPECT_EQ(enrollment.views[1].descriptor, DescribeView(image, kLire).descriptor);
  EXPECT_EQ(enrollment.thumbnails, (std::vector<std::string>{"", "tiny"}));
}

TEST(EnrollmentStreamTest, MessagesOutOfOrderOrInvalidEndTheStream) {
  constexpr auto kInvalid = grpc::StatusCode::INVALID_ARGUMENT;
  {
    EnrollmentStream stream(kLire, kMaxBytes);
    v1::EnrollRequest view = View(1, 0), empty;
    ExpectStatus(stream.Accept(&view), kInvalid, "the first message must be the header");
    ExpectStatus(stream.Accept(&empty), kInvalid, "empty request: set header or view");
    Enrollment enrollment;
    ExpectStatus(stream.ToEnrollment(kLimits, &enrollment), kInvalid,
                 "no header: nothing to enroll");
  }
  {
    EnrollmentStream stream(kLire, kMaxBytes);
    v1::EnrollRequest header = Header("mug");
    ASSERT_TRUE(stream.Accept(&header).ok());
    ExpectStatus(stream.Accept(&header), kInvalid, "the header may be sent only once");
    Enrollment enrollment;
    ExpectStatus(stream.ToEnrollment(kLimits, &enrollment), kInvalid,
                 "no views: an object needs at least one");
  }
  EnrollmentStream stream(kLire, kMaxBytes);
  v1::EnrollRequest header = Header("bad name");
  ExpectStatus(stream.Accept(&header), kInvalid,
               "object name \"bad name\" has a character not allowed at position 3 (allowed: "
               "ASCII letters, digits, '_', '-', '.')");
  header = Header("mug", "[1]");
  ExpectStatus(stream.Accept(&header), kInvalid, "metadata must be a JSON object ({...})");
  header = Header("mug");
  header.mutable_header()->set_variant(v1::CEDD_FULL);
  ExpectStatus(stream.Accept(&header), kInvalid,
               "header.variant is cedd-full but this server's models are cedd-lire; variants "
               "cannot be mixed");
  // A view is read only once the stream ends; the first bad one names its position.
  header = Header("mug");
  v1::EnrollRequest good = View(1, 0), bad = View(8, 0);
  ASSERT_TRUE(stream.Accept(&header).ok());
  ASSERT_TRUE(stream.Accept(&good).ok());
  ASSERT_TRUE(stream.Accept(&bad).ok());
  Enrollment enrollment;
  ExpectStatus(stream.ToEnrollment(kLimits, &enrollment), kInvalid,
               "view 1: view.cedd value 8 at index 0 is outside 0..7");
}

TEST(EnrollmentStreamTest, AtMostTheStoresViewsPerObject) {
  EnrollmentStream stream(kLire, kMaxBytes);
  v1::EnrollRequest header = Header("many");
  ASSERT_TRUE(stream.Accept(&header).ok());
  for (std::size_t i = 0; i < kMaxViewsPerObject; ++i) {
    v1::EnrollRequest view = View(1, static_cast<double>(i));
    ASSERT_TRUE(stream.Accept(&view).ok()) << i;
  }
  v1::EnrollRequest one_more = View(1, 0);
  ExpectStatus(stream.Accept(&one_more), grpc::StatusCode::RESOURCE_EXHAUSTED,
               "more than 1024 views for one object");
}

TEST(EnrollmentStreamTest, RefusesViewsBeyondItsByteLimitNamingTheFlag) {
  // Each view is a little over kCeddSize bytes on the wire; three fit in 600 bytes, four do not.
  EnrollmentStream stream(kLire, 600);
  v1::EnrollRequest header = Header("mug");
  ASSERT_TRUE(stream.Accept(&header).ok());
  for (int i = 0; i < 3; ++i) {
    v1::EnrollRequest view = View(1, i * 10.0);
    ASSERT_TRUE(stream.Accept(&view).ok()) << i;
  }
  v1::EnrollRequest fourth = View(1, 30.0);
  ExpectStatus(stream.Accept(&fourth), grpc::StatusCode::RESOURCE_EXHAUSTED,
               "the enrollment's views are more than 600 bytes (--max-enrollment-bytes)");
}

}  // namespace
}  // namespace orbit::server
