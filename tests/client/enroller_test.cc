// The device-side description of views for enrollment (client/enroller.h, ComputeView): what
// the server will store for an image or a region of it.
#include "client/enroller.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "client/image_file.h"
#include "client/models_client.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/view_description.h"
#include "evaluation/capture_generator.h"
#include "tests/support/capture_walks.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::CoilImage;

TEST(EnrollerTest, ComputeViewIsTheCeddAndTypicalDistanceOfTheImageOrRegion) {
  const cv::Mat image = CoilImage(7, 40);
  const v1::View view =
      ComputeView({image, 40.0, std::nullopt, 12.5}, DescriptorVariant::kCeddLire, /*seed=*/9);
  const DescriptorValues expected = ExtractCedd(image, DescriptorVariant::kCeddLire).values;
  EXPECT_EQ(view.cedd(), std::string(expected.begin(), expected.begin() + kCeddSize));
  EXPECT_EQ(view.azimuth_deg(), 40.0);
  EXPECT_EQ(view.elevation_deg(), 12.5);
  ASSERT_TRUE(view.has_typical_distance());
  EXPECT_DOUBLE_EQ(view.typical_distance(),
                   DescribeView(image, DescriptorVariant::kCeddLire, 9).typical_distance);
  EXPECT_GT(view.typical_distance(), 0.0);
  EXPECT_LT(view.typical_distance(), 1.0);

  // With a region, everything is computed on the region alone, as if the device had cropped.
  const cv::Rect region(20, 30, 80, 70);
  const v1::View cropped =
      ComputeView({image, 40.0, region, std::nullopt}, DescriptorVariant::kCeddFull, 9);
  const cv::Mat crop = image(region).clone();
  const DescriptorValues crop_cedd = ExtractCedd(crop, DescriptorVariant::kCeddFull).values;
  EXPECT_EQ(cropped.cedd(), std::string(crop_cedd.begin(), crop_cedd.begin() + kCeddSize));
  EXPECT_DOUBLE_EQ(cropped.typical_distance(),
                   DescribeView(crop, DescriptorVariant::kCeddFull, 9).typical_distance);
  EXPECT_FALSE(cropped.has_elevation_deg());

  EXPECT_THROW(
      ComputeView({image, 0, cv::Rect(100, 100, 40, 40), {}}, DescriptorVariant::kCeddLire, 1),
      std::invalid_argument);
  EXPECT_THROW(ComputeView({cv::Mat(), 0, {}, {}}, DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
}

TEST(EnrollerTest, FromVideoStoresTheViewsOfItsChosenFramesGivenAsImages) {
  const testing::ScratchDir dir;
  const testing::WrittenWalk walk = testing::WriteWalk(dir, testing::CoilWalk(3, 40, 200));

  testing::ServerProcess server;
  const Connection connection(testing::At(server.address()));
  Enroller enroller(connection, {.seed = 5, .threads = 2});
  CaptureReader reader(walk.video, OrientationLog::ReadFile(walk.log),
                       {.first_box = walk.capture.true_boxes[0]});
  const Enroller::VideoEnrollment enrolled = enroller.FromVideo("walked", reader);
  const std::vector<CaptureView>& chosen = enrolled.selection.views;
  // 40 frames over 200 degrees, one per 5-degree step but for the log's 3 degrees of noise:
  // some steps get two frames and others none; 4 frames are blurred, 3 noisy.
  ASSERT_GE(chosen.size(), 18u);
  EXPECT_EQ(enrolled.object.view_count(), static_cast<int>(chosen.size()));

  // The same frames, saved as lossless images, enrolled the old way with their azimuths and
  // the tracked regions: view for view the same descriptors and typical distances.
  cv::VideoCapture video(walk.video);
  std::vector<EnrollmentImage> images;
  cv::Mat frame;
  for (long f = 0, c = 0; video.read(frame) && c < static_cast<long>(chosen.size()); ++f) {
    if (f != chosen[c].frame_index) continue;
    const std::string file = (dir / ("frame" + std::to_string(f) + ".png")).string();
    cv::imwrite(file, frame);
    images.push_back({ReadImageFile(file), chosen[c].image.azimuth_deg, chosen[c].region, {}});
    ++c;
  }
  ASSERT_EQ(images.size(), chosen.size());
  std::vector<v1::View> expected = enroller.ComputeViews(images);
  const v1::GetObjectResponse stored =
      ModelsClient(connection).GetObject(ObjectByName("walked"), true);
  ASSERT_EQ(stored.views_size(), static_cast<int>(expected.size()));
  std::sort(expected.begin(), expected.end(), [](const v1::View& a, const v1::View& b) {
    return a.azimuth_deg() < b.azimuth_deg();
  });  // the store orders views by azimuth
  for (int v = 0; v < stored.views_size(); ++v) {
    EXPECT_EQ(stored.views(v).cedd(), expected[v].cedd()) << v;
    EXPECT_EQ(stored.views(v).azimuth_deg(), expected[v].azimuth_deg()) << v;
    EXPECT_DOUBLE_EQ(stored.views(v).typical_distance(), expected[v].typical_distance()) << v;
  }

  // A capture whose object is lost at once has nothing to enroll: refused before any call.
  CaptureReader whole(walk.video, OrientationLog::ReadFile(walk.log),
                      {.boxes = std::vector<cv::Rect>(40, cv::Rect(400, 300, 10, 10))});
  EXPECT_EQ(testing::ErrorMessageOf([&] { enroller.FromVideo("nothing", whole); }),
            "no usable frame in " + walk.video +
                " (40 read, 40 lost, 0 too blurred or noisy): nothing to enroll for nothing");
}

}  // namespace
}  // namespace orbit
