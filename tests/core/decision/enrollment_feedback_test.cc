// AssessEnrollment on hand-made objects whose gaps, repeats and confusions are counted by hand.
#include "core/decision/enrollment_feedback.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "tests/support/hand_made_descriptors.h"

namespace orbit {
namespace {

using testing::Bins;

ObjectModel Object(ObjectId id, std::vector<std::pair<double, DescriptorValues>> views) {
  ObjectModel model;
  model.id = id;
  model.name = "obj" + std::to_string(id);
  for (const auto& [azimuth, descriptor] : views) {
    ModelView view;
    view.descriptor = descriptor;
    view.azimuth = azimuth;
    model.views.push_back(view);
  }
  return model;
}

void ExpectConfusion(const Confusion& confusion, ObjectId object, double similarity, int closer) {
  EXPECT_EQ(confusion.object, object);
  EXPECT_DOUBLE_EQ(confusion.similarity, similarity) << "object " << object;
  EXPECT_EQ(confusion.closer_views, closer) << "object " << object;
}

TEST(EnrollmentFeedbackTest, FindsGapsAcrossZeroAndRepeatedViews) {
  // Views at 350, 10, 20 and 120: gaps 20 -> 120 (100) and 120 -> 350 (230); 350 -> 10 is 20.
  // The view at 20 equals the one at 10: a repeat (the earlier one in azimuth order stays).
  const ObjectModel object = Object(
      1,
      {{120, Bins({{0, 7}})}, {10, Bins({{1, 7}})}, {20, Bins({{1, 7}})}, {350, Bins({{2, 7}})}});
  const auto empty = ViewIndex(DescriptorVariant::kCeddLire).Snapshot();
  const EnrollmentFeedback feedback = AssessEnrollment(object, *empty);
  ASSERT_EQ(feedback.gaps.size(), 2u);
  EXPECT_EQ(feedback.gaps[0].from, 20);
  EXPECT_EQ(feedback.gaps[0].to, 120);
  EXPECT_EQ(feedback.gaps[0].width(), 100);
  EXPECT_EQ(feedback.gaps[1].from, 120);
  EXPECT_EQ(feedback.gaps[1].to, 350);
  EXPECT_EQ(feedback.gaps[1].width(), 230);
  EXPECT_EQ(feedback.redundant_azimuths, std::vector<double>{20});
  EXPECT_TRUE(feedback.confusable.empty());
}

TEST(EnrollmentFeedbackTest, RanksTheObjectsItCouldBeTakenFor) {
  // The new object's views: A = bins {0:4} and B = bins {1:4}; its own views share nothing
  // (TC(A, B) = 0), so any positive similarity elsewhere is closer than its own.
  const ObjectModel object = Object(3, {{0, Bins({{0, 4}})}, {180, Bins({{1, 4}})}});
  // obj1 holds A exactly (TC 1 with A, 0 with B): similarity (1 + 0) / 2 = 0.5, 1 view closer.
  // obj2 holds {0:4, 1:4}: TC 16 / (16 + 32 - 16) = 0.5 with A and with B: similarity 0.5,
  // 2 views closer; ties go to the lower id, so obj1 first.
  // obj4 holds {2:4}: similarity 0.
  const ViewIndex index({Object(1, {{0, Bins({{0, 4}})}}), Object(2, {{0, Bins({{0, 4}, {1, 4}})}}),
                         Object(4, {{0, Bins({{2, 4}})}}), object});
  const EnrollmentFeedback feedback = AssessEnrollment(object, *index.Snapshot());
  ASSERT_EQ(feedback.confusable.size(), 3u);  // the object itself is not among them
  ExpectConfusion(feedback.confusable[0], 1, 0.5, 1);
  ExpectConfusion(feedback.confusable[1], 2, 0.5, 2);
  ExpectConfusion(feedback.confusable[2], 4, 0, 0);
  // Two views 180 apart: both gaps are 180 wide.
  EXPECT_EQ(feedback.gaps.size(), 2u);
}

// Above kScanEveryObjectUpTo objects the confusable ones come from candidates, and
// are still the right ones, scored exactly. The new object's 8 views, 45 degrees apart, are bins
// {v: 4} for v = 0..7 (no two alike). obj1 holds views 0 and 1 exactly: (1 + 1) / 8 = 0.25, 2
// views closer. obj2 holds view 2: 1 / 8 = 0.125, 1 closer. obj3 holds {3: 4, 4: 4}, TC
// 16 / (16 + 32 - 16) = 0.5 with views 3 and 4: 1 / 8 = 0.125, 2 closer (after obj2, the lower
// id). 998 other objects share no bin with it.
TEST(EnrollmentFeedbackTest, ALargeCatalogueStillNamesTheObjectsItCouldBeTakenFor) {
  std::vector<std::pair<double, DescriptorValues>> views;
  for (int v = 0; v < 8; ++v) views.push_back({45.0 * v, Bins({{v, 4}})});
  const ObjectModel object = Object(5000, views);
  std::vector<ObjectModel> catalogue = {Object(1, {{0, Bins({{0, 4}})}, {45, Bins({{1, 4}})}}),
                                        Object(2, {{90, Bins({{2, 4}})}}),
                                        Object(3, {{135, Bins({{3, 4}, {4, 4}})}})};
  for (ObjectId id = 4; catalogue.size() <= kScanEveryObjectUpTo; ++id) {
    catalogue.push_back(Object(id, {{0, Bins({{8 + static_cast<int>(id % 136), 3}})}}));
  }
  const ViewIndex index(catalogue);
  const EnrollmentFeedback feedback = AssessEnrollment(object, *index.Snapshot());
  ASSERT_EQ(feedback.confusable.size(), 3u);
  ExpectConfusion(feedback.confusable[0], 1, 0.25, 2);
  ExpectConfusion(feedback.confusable[1], 2, 0.125, 1);
  ExpectConfusion(feedback.confusable[2], 3, 0.125, 2);
}

TEST(EnrollmentFeedbackTest, OneViewLeavesTheWholeCircleOpen) {
  const ObjectModel object = Object(1, {{45, Bins({{0, 4}})}});
  const auto empty = ViewIndex(DescriptorVariant::kCeddLire).Snapshot();
  const EnrollmentFeedback feedback = AssessEnrollment(object, *empty);
  ASSERT_EQ(feedback.gaps.size(), 1u);
  EXPECT_EQ(feedback.gaps[0].width(), 360);
  EXPECT_THROW(AssessEnrollment(Object(2, {}), *empty), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
