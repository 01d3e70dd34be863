// IndexedObject: a model's views with what every frame's comparison needs precomputed, checked
// against values worked out by hand.
#include "core/indexed_object.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/hand_made_descriptors.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::Bins;

ObjectModel Model(std::vector<DescriptorValues> descriptors, std::vector<double> azimuths) {
  ObjectModel model;
  model.id = 9;
  for (std::size_t v = 0; v < descriptors.size(); ++v) {
    ModelView view;
    view.descriptor = descriptors[v];
    view.azimuth = azimuths[v];
    model.views.push_back(view);
  }
  return model;
}

// Three views: bin d of view v sits at view_bins()[d * 3 + v]; c.c per view.
TEST(IndexedObjectTest, ViewBinsHoldEachBinOfEveryViewSideBySide) {
  const IndexedObject object(
      Model({Bins({{0, 1}, {143, 7}}), Bins({{0, 2}, {5, 3}}), Bins({{5, 4}})}, {0, 120, 240}));
  const std::vector<std::uint8_t>& bins = object.view_bins();
  ASSERT_EQ(bins.size(), 144u * 3);
  EXPECT_EQ((std::vector<std::uint8_t>(bins.begin(), bins.begin() + 3)),
            (std::vector<std::uint8_t>{1, 2, 0}));  // bin 0
  EXPECT_EQ((std::vector<std::uint8_t>(bins.begin() + 15, bins.begin() + 18)),
            (std::vector<std::uint8_t>{0, 3, 4}));  // bin 5
  EXPECT_EQ((std::vector<std::uint8_t>(bins.end() - 3, bins.end())),
            (std::vector<std::uint8_t>{7, 0, 0}));  // bin 143
  int non_zero = 0;
  for (const std::uint8_t value : bins) non_zero += value != 0;
  EXPECT_EQ(non_zero, 5);
  // 1 + 49, 4 + 9, 16.
  EXPECT_EQ(object.squared_norms(), (std::vector<std::int32_t>{50, 13, 16}));
}

TEST(IndexedObjectTest, AzimuthsAreNormalisedAndOrdered) {
  const IndexedObject object(
      Model({Bins({{0, 1}}), Bins({{1, 1}}), Bins({{2, 1}})}, {370, -90, 180}));
  EXPECT_EQ(object.model().views[0].azimuth, 10);
  EXPECT_EQ(object.model().views[1].azimuth, 270);
  EXPECT_EQ(object.views_by_azimuth(), (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(object.sorted_azimuths(), (std::vector<double>{10, 180, 270}));
}

TEST(IndexedObjectTest, AModelWithoutViewsOrWithABadViewIsRefused) {
  EXPECT_EQ(testing::ErrorMessageOf([] { IndexedObject object(Model({}, {})); }),
            "object 9 has no views");
  EXPECT_EQ(testing::ErrorMessageOf([] {
              IndexedObject object(
                  Model({Bins({{0, 1}})}, {std::numeric_limits<double>::infinity()}));
            }),
            "object 9: a view's azimuth is not finite");
  EXPECT_EQ(testing::ErrorMessageOf([] { IndexedObject object(Model({Bins({{4, 8}})}, {0})); }),
            "object 9 descriptor value 8 at index 4 is outside 0..7");
}

}  // namespace
}  // namespace orbit
