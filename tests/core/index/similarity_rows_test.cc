// SimilarityRows: a session's cache of TC(window frame, model view), against values computed by
// hand, following the window as it slides and forgetting objects a new model set dropped.
#include "core/index/similarity_rows.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/descriptor/similarity.h"
#include "tests/support/coil_models.h"
#include "tests/support/hand_made_descriptors.h"

namespace orbit {
namespace {

using testing::Bins;
using testing::CoilObject;

// Views `apart` degrees from each other, from azimuth 0: 120 is too far apart to blend.
ObjectModel Model(ObjectId id, std::vector<DescriptorValues> views, double apart = 120) {
  ObjectModel model;
  model.id = id;
  model.name = "obj" + std::to_string(id);
  double azimuth = 0;
  for (DescriptorValues& descriptor : views) {
    model.views.push_back({std::move(descriptor), azimuth, std::nullopt, 0.1});
    azimuth += apart;
  }
  return model;
}

QueryFrame Frame(const DescriptorValues& values) {
  return {{DescriptorVariant::kCeddLire, values}, std::nullopt};
}

const DescriptorValues kQuery = Bins({{0, 4}});         // q.q = 16
const DescriptorValues kHalf = Bins({{0, 4}, {1, 4}});  // q.v = 16, v.v = 32: TC 16/32 = 1/2
const DescriptorValues kDisjoint = Bins({{1, 4}});      // TC 0

TEST(SimilarityRowsTest, RowsHoldEachFramesTanimotoWithEachView) {
  const IndexedObject object(Model(1, {kQuery, kHalf, kDisjoint}));
  SimilarityRows rows;
  const std::vector<QueryFrame> window{Frame(kQuery), Frame(kDisjoint)};
  rows.PushFrame();
  rows.PushFrame();
  const ObjectRows got = rows.For(window, object);
  ASSERT_EQ(got.rows.size(), 2u);
  EXPECT_EQ(got.object, &object);
  EXPECT_EQ(std::vector<float>(got.rows[0].begin(), got.rows[0].end()),
            (std::vector<float>{1.0f, 0.5f, 0.0f}));
  // kDisjoint against kHalf: 16 / (16 + 32 - 16) = 1/2.
  EXPECT_EQ(std::vector<float>(got.rows[1].begin(), got.rows[1].end()),
            (std::vector<float>{0.0f, 0.5f, 1.0f}));
  // Each row's nearest view, as the blend and the unknown statistic read it.
  ASSERT_EQ(got.nearest.size(), 2u);
  EXPECT_EQ(got.nearest[0].view, 0);
  EXPECT_EQ(got.nearest[0].similarity, 1.0f);
  EXPECT_EQ(got.nearest[1].view, 2);
  EXPECT_EQ(got.nearest[1].similarity, 1.0f);
}

// Views (4, 0) and (0, 4) 20 degrees apart blend into (2, 2). A frame (2, 2) is each view's TC
// 8 / (8 + 16 - 8) = 1/2 and the blend's 1; a frame (4, 0) is the first view's 1 and the blend's
// 8 / (16 + 8 - 8) = 1/2. Views 120 degrees apart are not blended: 0.
TEST(SimilarityRowsTest, EachRowKnowsItsBestBlendOfNeighbouringViews) {
  const DescriptorValues first = Bins({{0, 4}}), second = Bins({{1, 4}});
  const IndexedObject object(Model(1, {first, second}, 20));
  const DescriptorValues between = Bins({{0, 2}, {1, 2}});
  float blended = -1;
  EXPECT_EQ(SimilarityRow(between, object, &blended), (std::vector<float>{0.5f, 0.5f}));
  EXPECT_EQ(blended, 1.0f);
  EXPECT_EQ(SimilarityRow(first, object, &blended), (std::vector<float>{1.0f, 0.0f}));
  EXPECT_EQ(blended, 0.5f);

  SimilarityRows rows;
  const std::vector<QueryFrame> window{Frame(between)};
  rows.PushFrame();
  const ObjectRows got = rows.For(window, object);
  ASSERT_EQ(got.nearest.size(), 1u);
  EXPECT_EQ(got.nearest[0].view, 0);
  EXPECT_EQ(got.nearest[0].similarity, 0.5f);
  EXPECT_EQ(got.nearest[0].blended, 1.0f);
  EXPECT_EQ(got.nearest[0].closest(), 1.0f);
  // Each pair's blend on its own, as the calibration reads some of them: the one pair here.
  std::vector<float> blends{0.25f, 0.25f};
  SimilarityRow(between, object, nullptr, &blends);
  EXPECT_EQ(blends, std::vector<float>{1.0f});
  SimilarityRow(first, object, &blended, &blends);
  EXPECT_EQ(blends, std::vector<float>{0.5f});
  EXPECT_EQ(blended, 0.5f);

  const IndexedObject far_apart(Model(2, {first, second}));
  SimilarityRow(between, far_apart, &blended);
  EXPECT_EQ(blended, 0.0f);
}

// Of equally near views the first is the nearest: the unknown statistic reads its typical
// distance, so which one must not depend on how the row was stored.
TEST(SimilarityRowsTest, TheNearestOfEqualViewsIsTheFirst) {
  const IndexedObject object(Model(1, {kDisjoint, kHalf, kHalf}));
  SimilarityRows rows;
  const std::vector<QueryFrame> window{Frame(kQuery)};
  rows.PushFrame();
  const ObjectRows got = rows.For(window, object);
  ASSERT_EQ(got.nearest.size(), 1u);
  EXPECT_EQ(got.nearest[0].view, 1);
  EXPECT_EQ(got.nearest[0].similarity, 0.5f);
}

// The row is Tanimoto() view by view, rounded to float, on real descriptors and on the empty one
// (1 against an empty view, 0 against the others).
TEST(SimilarityRowsTest, RowsAreTanimotoOnCoilViews) {
  const IndexedObject object(CoilObject(7));
  std::vector<DescriptorValues> frames;
  for (const int n : {7, 8, 52}) {
    for (const ModelView& view : CoilObject(n).views) frames.push_back(view.descriptor);
  }
  frames.push_back(DescriptorValues{});
  for (const DescriptorValues& frame : frames) {
    const std::vector<float> row = SimilarityRow(frame, object);
    ASSERT_EQ(row.size(), object.model().views.size());
    for (std::size_t v = 0; v < row.size(); ++v) {
      ASSERT_EQ(row[v], static_cast<float>(Tanimoto(frame, object.model().views[v].descriptor)))
          << "view " << v;
    }
  }
  const IndexedObject empty_view(Model(2, {DescriptorValues{}, kQuery}));
  EXPECT_EQ(SimilarityRow(DescriptorValues{}, empty_view), (std::vector<float>{1.0f, 0.0f}));
}

// The largest products a descriptor can have are summed exactly: every bin at 7 gives a dot
// product of 144 x 49 = 7056. Against itself TC = 1; against every other bin at 7 (dot 3528,
// norms 7056 and 3528), 3528 / (7056 + 3528 - 3528) = 1/2; against every bin at 6, 6048 /
// (7056 + 5184 - 6048) = 6048 / 6192.
TEST(SimilarityRowsTest, TheLargestValuesAreSummedExactly) {
  DescriptorValues full, alternate, six;
  full.fill(7);
  six.fill(6);
  alternate.fill(0);
  for (std::size_t i = 0; i < alternate.size(); i += 2) alternate[i] = 7;
  const IndexedObject object(Model(1, {full, alternate, six}));
  const std::vector<float> row = SimilarityRow(full, object);
  EXPECT_EQ(row, (std::vector<float>{1.0f, 0.5f, static_cast<float>(6048.0 / 6192.0)}));
}

TEST(SimilarityRowsTest, AFrameThatLeftTakesItsRowsWithIt) {
  const IndexedObject object(Model(1, {kQuery, kHalf}));
  SimilarityRows rows;
  std::vector<QueryFrame> window{Frame(kQuery), Frame(kDisjoint)};
  rows.PushFrame();
  rows.PushFrame();
  rows.For(window, object);
  rows.DropOldest();
  window.erase(window.begin());
  const ObjectRows got = rows.For(window, object);
  ASSERT_EQ(got.rows.size(), 1u);
  EXPECT_EQ(std::vector<float>(got.rows[0].begin(), got.rows[0].end()),
            (std::vector<float>{0.0f, 0.5f}));
}

// The cache is keyed by address: an object built where a forgotten one lived gets its own rows.
// Without Forget the second object would read the first one's (1, 1/2 instead of 0, 1/2, 0).
TEST(SimilarityRowsTest, AForgottenObjectsRowsAreNotGivenToTheNextObjectAtItsAddress) {
  std::optional<IndexedObject> slot;
  slot.emplace(Model(1, {kQuery, kHalf}));
  const IndexedObject* address = &*slot;
  SimilarityRows rows;
  const std::vector<QueryFrame> window{Frame(kQuery)};
  rows.PushFrame();
  EXPECT_EQ(rows.For(window, *slot).rows[0][0], 1.0f);
  const std::vector<const IndexedObject*> removed{address};
  rows.Forget(removed);
  slot.emplace(Model(2, {kDisjoint, kHalf, kDisjoint}));
  ASSERT_EQ(&*slot, address);
  const ObjectRows got = rows.For(window, *slot);
  EXPECT_EQ(std::vector<float>(got.rows[0].begin(), got.rows[0].end()),
            (std::vector<float>{0.0f, 0.5f, 0.0f}));
}

TEST(SimilarityRowsTest, ForgettingOneObjectKeepsTheOthersRows) {
  const IndexedObject kept(Model(1, {kQuery}));
  const IndexedObject dropped(Model(2, {kHalf}));
  SimilarityRows rows;
  const std::vector<QueryFrame> window{Frame(kQuery)};
  rows.PushFrame();
  const float* before = rows.For(window, kept).rows[0].data();
  rows.For(window, dropped);
  const std::vector<const IndexedObject*> removed{&dropped};
  rows.Forget(removed);
  // The same stored row, not a recomputed one.
  EXPECT_EQ(rows.For(window, kept).rows[0].data(), before);
}

}  // namespace
}  // namespace orbit
