#include "evaluation/synthetic_object.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit {
namespace {

// A box whose four side faces are plain red, green, blue and white (faces[0..3]) and whose lid is
// grey, so that each pixel says which surface it sees.
SyntheticObject PlainBox() {
  SyntheticObject box;
  box.name = "plain";
  box.shape = SyntheticObject::Shape::kBox;
  const cv::Scalar colours[] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}, {255, 255, 255}};
  for (int f = 0; f < 4; ++f) box.faces[f] = cv::Mat(256, 256, CV_8UC3, colours[f]);
  box.top_colour = cv::Scalar(128, 128, 128);
  return box;
}

// The face a view's centre shows: 0-3 by its colour, -1 for anything else.
int CentreFace(const cv::Mat& view) {
  const cv::Vec3b p = view.at<cv::Vec3b>(view.rows / 2, view.cols / 2);
  const bool b = p[0] > 100, g = p[1] > 100, r = p[2] > 100;
  if (r && !g && !b) return 0;
  if (g && !r && !b) return 1;
  if (b && !r && !g) return 2;
  if (r && g && b) return 3;
  return -1;
}

// The camera circles the object as the azimuth grows: the front face (+z) at 0 degrees, then
// the faces in the order -x, -z, +x (the object turns counter-clockwise seen from above); the
// lid shows above the front, and the corners stay black.
TEST(SyntheticObjectTest, TheBoxTurnsFaceByFaceAsTheAzimuthGrows) {
  const SyntheticObject box = PlainBox();
  EXPECT_EQ(CentreFace(RenderView(box, 0)), 0);
  EXPECT_EQ(CentreFace(RenderView(box, 90)), 3);
  EXPECT_EQ(CentreFace(RenderView(box, 180)), 2);
  EXPECT_EQ(CentreFace(RenderView(box, 270)), 1);
  const cv::Mat front = RenderView(box, 0);
  ASSERT_EQ(front.size(), cv::Size(128, 128));
  ASSERT_EQ(front.type(), CV_8UC3);
  EXPECT_EQ(front.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));
  // The lid: a strip of grey just above the front face's top edge, seen from 20 degrees up and
  // lit at a grazing angle (the shading 0.35 + 0.65 cos takes its 128 to about 0.45 of it).
  int grey = 0;
  for (int y = 0; y < front.rows / 2; ++y) {
    const cv::Vec3b p = front.at<cv::Vec3b>(y, front.cols / 2);
    grey += p[0] == p[1] && p[1] == p[2] && p[0] > 40 && p[0] < 100;
  }
  EXPECT_GE(grey, 5);
}

// Rays cast once paint any object of their shape as RenderView does, pixel for pixel, at every
// size; rays of a box cannot paint a cylinder.
TEST(SyntheticObjectTest, CastRaysPaintEveryObjectOfTheirShape) {
  for (const int size : {128, 64}) {
    const ViewRays box_rays = CastViewRays(SyntheticObject::Shape::kBox, 35, size);
    const ViewRays can_rays = CastViewRays(SyntheticObject::Shape::kCylinder, 35, size);
    EXPECT_FALSE(box_rays.hits.empty());
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      const SyntheticObject object = RandomSyntheticObject(seed, "o");
      const ViewRays& rays = object.shape == SyntheticObject::Shape::kBox ? box_rays : can_rays;
      const ViewRays& other = object.shape == SyntheticObject::Shape::kBox ? can_rays : box_rays;
      EXPECT_EQ(cv::norm(RenderView(object, rays), RenderView(object, 35, size), cv::NORM_INF), 0)
          << "seed " << seed << ", size " << size;
      EXPECT_THROW(RenderView(object, other), std::invalid_argument);
    }
  }
}

// Objects drawn from different seeds look different; the same seed draws the same object.
TEST(SyntheticObjectTest, RandomObjectsAreFixedByTheirSeed) {
  const cv::Mat a = RenderView(RandomSyntheticObject(11, "a"), 10);
  EXPECT_EQ(cv::norm(a, RenderView(RandomSyntheticObject(11, "again"), 10), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(a, RenderView(RandomSyntheticObject(12, "b"), 10), cv::NORM_L1),
            20.0 * a.total());
}

}  // namespace
}  // namespace orbit
