// IndexedObject: a model's views with what every frame's comparison needs precomputed, checked
// against values worked out by hand.
#include "core/index/indexed_object.h"

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

// Three views: each bin of every view as the descriptors give it; c.c per view.
TEST(IndexedObjectTest, ViewBinsHoldEachBinOfEveryView) {
  const IndexedObject object(
      Model({Bins({{0, 1}, {143, 7}}), Bins({{0, 2}, {5, 3}}), Bins({{5, 4}})}, {0, 120, 240}));
  const ViewBins& bins = object.view_bins();
  ASSERT_EQ(bins.view_count(), 3u);
  EXPECT_EQ(bins.Value(0, 0), 1);
  EXPECT_EQ(bins.Value(0, 1), 2);
  EXPECT_EQ(bins.Value(5, 1), 3);
  EXPECT_EQ(bins.Value(5, 2), 4);
  EXPECT_EQ(bins.Value(143, 0), 7);
  int non_zero = 0;
  for (std::size_t d = 0; d < kDescriptorSize; ++d) {
    for (std::size_t v = 0; v < 3; ++v) non_zero += bins.Value(d, v) != 0;
  }
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

// Views at 20, 350, 60 and 200 degrees: in azimuth order 20, 60, 200, 350. Next to each other
// and at most kBlendViewsUpTo (90) degrees apart: 20 and 60, then 350 and 20 across 360. Each
// pair's |c_a + c_b|^2: (1, 3) gives 10, (3, 2) gives 13.
TEST(IndexedObjectTest, NeighbourPairsAreViewsNextInAzimuthAndCloseEnoughToBlend) {
  const IndexedObject object(
      Model({Bins({{0, 1}}), Bins({{0, 2}, {1, 2}}), Bins({{1, 3}}), Bins({{2, 1}})},
            {20, 350, 60, 200}));
  const std::vector<NeighbourPair>& pairs = object.neighbour_pairs();
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].first, 0);
  EXPECT_EQ(pairs[0].second, 2);
  EXPECT_EQ(pairs[0].sum_squared_norm, 10);
  EXPECT_EQ(pairs[1].first, 1);
  EXPECT_EQ(pairs[1].second, 0);
  EXPECT_EQ(pairs[1].sum_squared_norm, 13);

  // Exactly 90 degrees apart is close enough, once: the way back round is 270.
  EXPECT_EQ(
      IndexedObject(Model({Bins({{0, 1}}), Bins({{1, 1}})}, {0, 90})).neighbour_pairs().size(), 1u);
  // One view, or two at different elevations: nothing to blend.
  EXPECT_TRUE(IndexedObject(Model({Bins({{0, 1}})}, {0})).neighbour_pairs().empty());
  ObjectModel tilted = Model({Bins({{0, 1}}), Bins({{1, 1}})}, {0, 20});
  tilted.views[1].elevation = 30;
  EXPECT_TRUE(IndexedObject(tilted).neighbour_pairs().empty());
}

TEST(IndexedObjectTest, AModelWithoutViewsOrWithABadViewIsRefused) {
  EXPECT_EQ(testing::ErrorMessageOf([] { IndexedObject object(Model({}, {})); }),
            "object 9 has no views");
  EXPECT_EQ(
      testing::ErrorMessageOf([] {
        IndexedObject object(Model({Bins({{0, 1}})}, {std::numeric_limits<double>::infinity()}));
      }),
      "object 9: a view's azimuth is not finite");
  EXPECT_EQ(testing::ErrorMessageOf([] {
              IndexedObject object(Model({Bins({{4, 8}})}, {0}));
            }),
            "object 9 descriptor value 8 at index 4 is outside 0..7");
}

}  // namespace
}  // namespace orbit
