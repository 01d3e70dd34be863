#include "core/decision/active_vision.h"

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

// An object with one view per 45-degree sector (azimuths 0, 45, ..., 315), every view equal to
// `common` except the view in sector `odd_sector`, which is `odd`.
IndexedObject Object(ObjectId id, int odd_sector, const DescriptorValues& odd) {
  DescriptorValues common{};
  common[0] = 4;
  common[30] = 2;
  ObjectModel model;
  model.id = id;
  for (int s = 0; s < 8; ++s)
    model.views.push_back({s == odd_sector ? odd : common, s * 45.0, {}, 0});
  return IndexedObject(model);
}

DescriptorValues Bin(int bin, int value) {
  DescriptorValues v{};
  v[bin] = static_cast<std::uint8_t>(value);
  return v;
}

// Two objects identical but for sector 2 ([90, 135)), where they are as different as can be.
TEST(ActiveVisionTest, MovesTowardTheSideWhereAnAmbiguousPairDiffers) {
  const IndexedObject a = Object(1, 2, Bin(10, 7));
  const IndexedObject b = Object(2, 2, Bin(100, 7));
  // Both seen at 50 degrees (sector 1): to the right lies sector 2.
  const std::vector<MoveCandidate> at_50 = {{&a, 50}, {&b, 50}};
  EXPECT_EQ(SuggestMove(at_50, 8), SuggestedMove::kRight);
  EXPECT_DOUBLE_EQ(SideSeparation(at_50, 8, +45).smallest, 1.0);  // disjoint bins: TC = 0
  EXPECT_DOUBLE_EQ(SideSeparation(at_50, 8, -45).smallest, 0.0);  // identical views
  // Seen at 150 degrees (sector 3): sector 2 is to the left.
  const std::vector<MoveCandidate> at_150 = {{&a, 150}, {&b, 150}};
  EXPECT_EQ(SuggestMove(at_150, 8), SuggestedMove::kLeft);
  // Across 0/360: seen at 370 = 10 degrees (sector 0) with the odd sector 7 to the left.
  const IndexedObject c = Object(3, 7, Bin(10, 7));
  const IndexedObject d = Object(4, 7, Bin(100, 7));
  const std::vector<MoveCandidate> at_370 = {{&c, 370}, {&d, 370}};
  EXPECT_EQ(SuggestMove(at_370, 8), SuggestedMove::kLeft);
}

// A side the window has already seen (a frame on it less than 1.5 sectors away) is not suggested
// when the other side is new, whatever the averaged views say; when both or neither are seen,
// the averaged views decide as before.
TEST(ActiveVisionTest, PrefersTheSideNotYetSeen) {
  const IndexedObject a = Object(1, 2, Bin(10, 7));
  const IndexedObject b = Object(2, 2, Bin(100, 7));
  const std::vector<MoveCandidate> at_50 = {{&a, 50}, {&b, 50}};  // the views differ on the right
  const std::vector<double> came_from_the_right = {40};           // a frame 40 degrees to the right
  EXPECT_EQ(SuggestMove(at_50, 8, came_from_the_right), SuggestedMove::kLeft);
  const std::vector<double> came_from_the_left = {-30, -60};
  EXPECT_EQ(SuggestMove(at_50, 8, came_from_the_left), SuggestedMove::kRight);
  const std::vector<double> both_sides = {44, -44};
  EXPECT_EQ(SuggestMove(at_50, 8, both_sides), SuggestedMove::kRight);
  const std::vector<double> near_here = {20, -20};
  EXPECT_EQ(SuggestMove(at_50, 8, near_here), SuggestedMove::kRight);
  const std::vector<double> across_360 = {-315};  // 45 degrees to the right, written round
  EXPECT_EQ(SuggestMove(at_50, 8, across_360), SuggestedMove::kLeft);
  // Seen at 150, the views differ on the left; a step of 20 degrees came from there: RIGHT. A
  // frame 70 degrees away (more than 1.5 sectors of 45) does not count: LEFT.
  const std::vector<MoveCandidate> at_150 = {{&a, 150}, {&b, 150}};
  const std::vector<double> one_step_back = {-20};
  EXPECT_EQ(SuggestMove(at_150, 8, one_step_back), SuggestedMove::kRight);
  const std::vector<double> far_back = {-70, 180};
  EXPECT_EQ(SuggestMove(at_150, 8, far_back), SuggestedMove::kLeft);
  // One candidate dominates: no move, seen or not.
  const std::vector<MoveCandidate> alone = {{&a, 50}};
  EXPECT_EQ(SuggestMove(alone, 8, came_from_the_right), SuggestedMove::kNone);
}

TEST(ActiveVisionTest, NoMoveWhenOneCandidateDominatesOrNothingHelps) {
  const IndexedObject a = Object(1, 2, Bin(10, 7));
  const IndexedObject twin = Object(2, 2, Bin(10, 7));
  const std::vector<MoveCandidate> alone = {{&a, 50}};
  EXPECT_EQ(SuggestMove(alone, 8), SuggestedMove::kNone);
  const std::vector<MoveCandidate> twins = {{&a, 50}, {&twin, 50}};
  EXPECT_EQ(SuggestMove(twins, 8), SuggestedMove::kNone);
  EXPECT_THROW(SuggestMove(twins, 1), std::invalid_argument);
}

// Three candidates: on the right, a and b differ completely but b and c are the same; on the
// left every pair differs a little. The pair that stays confused decides: LEFT, although the
// right side has the larger distance sum.
TEST(ActiveVisionTest, TheMostConfusablePairDecides) {
  DescriptorValues left_a = Bin(0, 4), left_b = Bin(0, 4), left_c = Bin(0, 4);
  left_b[1] = 2;
  left_c[2] = 2;
  const auto make = [](ObjectId id, const DescriptorValues& left, const DescriptorValues& right) {
    DescriptorValues common{};
    common[50] = 3;
    ObjectModel model;
    model.id = id;
    for (int s = 0; s < 8; ++s) {
      model.views.push_back({s == 0 ? left : s == 2 ? right : common, s * 45.0, {}, 0});
    }
    return IndexedObject(model);
  };
  const IndexedObject a = make(1, left_a, Bin(10, 7));
  const IndexedObject b = make(2, left_b, Bin(100, 7));
  const IndexedObject c = make(3, left_c, Bin(100, 7));
  const std::vector<MoveCandidate> candidates = {{&a, 60}, {&b, 60}, {&c, 60}};
  const Separation right = SideSeparation(candidates, 8, +45);
  const Separation left = SideSeparation(candidates, 8, -45);
  EXPECT_DOUBLE_EQ(right.smallest, 0.0);
  EXPECT_DOUBLE_EQ(right.sum, 2.0);
  // a.b = 16, a.a = 16, b.b = 20: TC = 16/20, distance 0.2 (a,c likewise); b.c = 16 / 24.
  EXPECT_DOUBLE_EQ(left.smallest, 0.2);
  EXPECT_NEAR(left.sum, 0.2 + 0.2 + (1 - 16.0 / 24), 1e-12);
  EXPECT_EQ(SuggestMove(candidates, 8), SuggestedMove::kLeft);
}

}  // namespace
}  // namespace orbit
