#include "evaluation/distractor_objects.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/descriptor/similarity.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

// The same seed gives the same models; ids, names and azimuths are as documented; progress
// counts every object.
TEST(DistractorObjectsTest, AreDrawnFromTheSeedAloneWithTheirIdsNamesAndViews) {
  std::vector<int> reported;
  const std::vector<ObjectModel> first =
      MakeDistractors(3, DescriptorVariant::kCeddLire, 101, 7, 2,
                      [&](int done, int count) { reported.push_back(done * 10 + count); });
  const std::vector<ObjectModel> again =
      MakeDistractors(3, DescriptorVariant::kCeddLire, 101, 7, 1, {});
  ASSERT_EQ(first.size(), 3u);
  EXPECT_EQ(first, again);
  EXPECT_EQ(reported, (std::vector<int>{13, 23, 33}));
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(first[k].id, 101 + k);
    EXPECT_EQ(first[k].name, "distractor" + std::to_string(k + 1));
    EXPECT_EQ(first[k].variant, DescriptorVariant::kCeddLire);
    ASSERT_EQ(first[k].views.size(), static_cast<std::size_t>(kDistractorViews));
    EXPECT_EQ(first[k].views[1].azimuth, 5.0);
  }
  EXPECT_NE(MakeDistractors(1, DescriptorVariant::kCeddLire, 1, 8, 1, {})[0].views[0],
            first[0].views[0]);
  EXPECT_TRUE(MakeDistractors(0, DescriptorVariant::kCeddLire, 1, 7, 1, {}).empty());
  // Distractor 2 alone, as `orbit import --layout distractors --objects 2` makes it.
  const DistractorObjects seven(7, 1);
  EXPECT_EQ(seven.Views(2, DescriptorVariant::kCeddLire, 2), first[1].views);
  EXPECT_THROW(seven.Views(0, DescriptorVariant::kCeddLire, 1), std::invalid_argument);
  EXPECT_THROW(seven.Views(kMaxDistractors + 1, DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
}

// Each distractor is its own object: a view is more like its own object's next view than like
// any view of another distractor, for most views.
TEST(DistractorObjectsTest, EachLooksLikeItselfMoreThanLikeTheOthers) {
  const std::vector<ObjectModel> models =
      MakeDistractors(6, DescriptorVariant::kCeddLire, 1, 3, 2, {});
  int own_closer = 0, views = 0;
  for (std::size_t o = 0; o < models.size(); ++o) {
    for (int v = 0; v < kDistractorViews; v += 6) {
      const DescriptorValues& view = models[o].views[v].descriptor;
      const double own = Tanimoto(view, models[o].views[(v + 1) % kDistractorViews].descriptor);
      double other = 0;
      for (std::size_t p = 0; p < models.size(); ++p) {
        if (p == o) continue;
        for (const ModelView& w : models[p].views)
          other = std::max(other, Tanimoto(view, w.descriptor));
      }
      own_closer += own > other;
      ++views;
    }
  }
  EXPECT_GE(own_closer, views * 9 / 10) << own_closer << " of " << views;
}

TEST(DistractorObjectsTest, ACountOutsideItsRangeIsRefused) {
  EXPECT_EQ(testing::ErrorMessageOf([] {
              MakeDistractors(kMaxDistractors + 1, DescriptorVariant::kCeddLire, 1, 1, 1, {});
            }),
            "distractors must be in 0..100000, got 100001");
}

}  // namespace
}  // namespace orbit
