// The store loaded into the engines' view index at start-up: every object searchable, variants
// never mixed.
#include "storage/view_index_loading.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;
using testing::SyntheticObject;
using testing::SyntheticView;

TEST(StoreVariantTest, IsThatOfTheStoredObjectsAndNoneForAnEmptyStore) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  EXPECT_EQ(StoreVariant(store), std::nullopt);
  Enrollment full = SyntheticObject("mug", 2);
  full.variant = DescriptorVariant::kCeddFull;
  store.Enroll(full);
  EXPECT_EQ(StoreVariant(store), DescriptorVariant::kCeddFull);
}

TEST(LoadViewIndexTest, EveryStoredViewIsFoundAtItsObjectAndAzimuth) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("a", 4, 1));   // views at 0, 90, 180, 270 with seeds 1..4
  store.Enroll(SyntheticObject("b", 4, 11));  // seeds 11..14
  store.Enroll(SyntheticObject("c", 4, 21));  // seeds 21..24

  for (SearchMode mode : {SearchMode::kExact, SearchMode::kKdTree}) {
    const std::unique_ptr<ViewIndex> index =
        LoadViewIndex(store, DescriptorVariant::kCeddLire, {.search = mode});
    const auto snapshot = index->Snapshot();
    EXPECT_EQ(snapshot->object_count(), 3u);
    EXPECT_EQ(snapshot->view_count(), 12u);
    // b's view with seed 13 was enrolled third, at 180 degrees.
    const std::vector<ViewMatch> best = snapshot->Search(SyntheticView(13, 0).descriptor, 1);
    ASSERT_EQ(best.size(), 1u);
    EXPECT_EQ(best[0].object, 2);
    EXPECT_EQ(best[0].azimuth, 180.0);
    EXPECT_EQ(best[0].similarity, 1.0);
  }
}

TEST(LoadViewIndexTest, AnEmptyStoreGivesAnEmptyIndexOfTheVariant) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  const std::unique_ptr<ViewIndex> index = LoadViewIndex(store, DescriptorVariant::kCeddFull);
  EXPECT_EQ(index->variant(), DescriptorVariant::kCeddFull);
  EXPECT_EQ(index->Snapshot()->object_count(), 0u);
}

TEST(LoadViewIndexTest, AnObjectOfAnotherVariantIsRefusedByName) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", {.create_if_missing = true});
  store.Enroll(SyntheticObject("lire", 2));
  Enrollment full = SyntheticObject("full", 2);
  full.variant = DescriptorVariant::kCeddFull;
  store.Enroll(full);

  try {
    LoadViewIndex(store, DescriptorVariant::kCeddLire);
    ADD_FAILURE() << "mixed variants loaded";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.code(), StoreError::Code::kIncompatible);
    EXPECT_STREQ(e.what(),
                 "the store holds object \"full\" (id 2) in variant cedd-full, not cedd-lire");
  }
}

}  // namespace
}  // namespace orbit
