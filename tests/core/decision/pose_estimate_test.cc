// EstimatePose: the rotation search on the winner, checked on small hand-made objects.
#include "core/decision/pose_estimate.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit {
namespace {

DescriptorValues Bin(int bin, int value = 7) {
  DescriptorValues values{};
  values[bin] = static_cast<std::uint8_t>(value);
  return values;
}

IndexedObject ObjectWithViews(const std::vector<std::pair<double, DescriptorValues>>& views) {
  ObjectModel model;
  model.id = 1;
  model.name = "obj1";
  for (const auto& [azimuth, descriptor] : views) {
    ModelView view;
    view.descriptor = descriptor;
    view.azimuth = azimuth;
    model.views.push_back(view);
  }
  return IndexedObject(std::move(model));
}

QueryFrame Frame(const DescriptorValues& values, std::optional<double> azimuth) {
  return {{DescriptorVariant::kCeddLire, values}, azimuth};
}

TEST(PoseEstimateTest, OneUnmistakableSideHasNoSpread) {
  const IndexedObject object =
      ObjectWithViews({{0, Bin(0)}, {90, Bin(1)}, {180, Bin(2)}, {270, Bin(3)}});
  const std::vector<QueryFrame> window{Frame(Bin(1), std::nullopt)};
  const PoseEstimate pose = EstimatePose(window, object);
  EXPECT_DOUBLE_EQ(pose.azimuth, 90);
  EXPECT_DOUBLE_EQ(pose.spread, 0);
}

TEST(PoseEstimateTest, OneFrameOfAMirroredObjectSpreadsToTheOtherSide) {
  // Front (10) and back (190) look the same, as a mug without its handle.
  const IndexedObject object =
      ObjectWithViews({{10, Bin(0)}, {100, Bin(1)}, {190, Bin(0)}, {280, Bin(3)}});
  const std::vector<QueryFrame> window{Frame(Bin(0), 500)};
  const PoseEstimate pose = EstimatePose(window, object);
  EXPECT_DOUBLE_EQ(pose.azimuth, 10);  // the tie goes to the smaller azimuth
  EXPECT_DOUBLE_EQ(pose.spread, 180);
}

TEST(PoseEstimateTest, TheTurnsSettleTheMirroredSide) {
  // The device saw bin 3 (280), then turned +90 and saw bin 0: only 10 follows 280 by 90 degrees
  // (190 would need bin 1 at 100 before it). Compass 500 degrees off.
  const IndexedObject object =
      ObjectWithViews({{10, Bin(0)}, {100, Bin(1)}, {190, Bin(0)}, {280, Bin(3)}});
  const std::vector<QueryFrame> window{Frame(Bin(3), 500 - 90), Frame(Bin(0), 500)};
  const PoseEstimate pose = EstimatePose(window, object);
  EXPECT_DOUBLE_EQ(pose.azimuth, 10);
  EXPECT_DOUBLE_EQ(pose.spread, 0);
  // The other way round it is 190: the device came from 100 (bin 1).
  const std::vector<QueryFrame> other{Frame(Bin(1), 410), Frame(Bin(0), 500)};
  EXPECT_DOUBLE_EQ(EstimatePose(other, object).azimuth, 190);
}

TEST(PoseEstimateTest, FramesWithoutAzimuthAddNothingButTheLatestCounts) {
  const IndexedObject object =
      ObjectWithViews({{10, Bin(0)}, {100, Bin(1)}, {190, Bin(0)}, {280, Bin(3)}});
  const std::vector<QueryFrame> window{Frame(Bin(3), std::nullopt), Frame(Bin(0), 500)};
  const PoseEstimate pose = EstimatePose(window, object);
  EXPECT_DOUBLE_EQ(pose.spread, 180);
}

TEST(PoseEstimateTest, RefusesAnEmptyWindow) {
  const IndexedObject object = ObjectWithViews({{0, Bin(0)}});
  EXPECT_THROW(EstimatePose({}, object), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
