// Tanimoto, its rotation-tolerant form and LIRE's distance (docs/design.md#similarity), on
// hand-computed cases and against LIRE's own distances.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "core/descriptor/similarity.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

constexpr int Bin(int texture_class, int colour) { return texture_class * kColourBins + colour; }

DescriptorValues Values(std::initializer_list<std::pair<int, int>> bins) {
  DescriptorValues v{};
  for (auto [index, value] : bins) v[index] = static_cast<std::uint8_t>(value);
  return v;
}

TEST(Tanimoto, HandComputedCases) {
  // q.c = 1*2 + 2*1 = 4, q.q = 5, c.c = 5: TC = 4 / (5 + 5 - 4) = 2/3.
  const auto q = Values({{0, 1}, {1, 2}});
  const auto c = Values({{0, 2}, {1, 1}});
  EXPECT_DOUBLE_EQ(Tanimoto(q, c), 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(TanimotoDistance(q, c), 1.0 - 4.0 / 6.0);
  // q.c = 7*7 = 49, q.q = 49 + 9 = 58, c.c = 49: TC = 49 / 58.
  EXPECT_DOUBLE_EQ(Tanimoto(Values({{10, 7}, {143, 3}}), Values({{10, 7}})), 49.0 / 58.0);
  EXPECT_DOUBLE_EQ(Tanimoto(q, q), 1.0);
  EXPECT_DOUBLE_EQ(Tanimoto(Values({{3, 5}}), Values({{4, 5}})), 0.0);  // disjoint
}

TEST(Tanimoto, ZeroVectors) {
  const DescriptorValues zero{};
  EXPECT_DOUBLE_EQ(Tanimoto(zero, zero), 1.0);
  EXPECT_DOUBLE_EQ(Tanimoto(zero, Values({{0, 1}})), 0.0);
  EXPECT_DOUBLE_EQ(Tanimoto(Values({{0, 1}}), zero), 0.0);
}

TEST(RollOrientation, MovesDirectionalClassesAndKeepsTheOthers) {
  // One block per class, each marked with its class number + 1 at colour bin 5.
  DescriptorValues v{};
  for (int cls = 0; cls < kTextureClasses; ++cls)
    v[Bin(cls, 5)] = static_cast<std::uint8_t>(cls + 1);
  const DescriptorValues once = RollOrientation(v, 1);
  EXPECT_EQ(once[Bin(0, 5)], 1);  // non-edge stays
  EXPECT_EQ(once[Bin(1, 5)], 2);  // non-directional stays
  EXPECT_EQ(once[Bin(4, 5)], 3);  // horizontal -> 45
  EXPECT_EQ(once[Bin(3, 5)], 5);  // 45 -> vertical
  EXPECT_EQ(once[Bin(5, 5)], 4);  // vertical -> 135
  EXPECT_EQ(once[Bin(2, 5)], 6);  // 135 -> horizontal
  EXPECT_EQ(RollOrientation(v, 4), v);
  EXPECT_EQ(RollOrientation(v, -1), RollOrientation(v, 3));
  EXPECT_EQ(RollOrientation(RollOrientation(v, 1), 1), RollOrientation(v, 2));
}

TEST(TanimotoRotationTolerant, FindsTheRolledMatch) {
  // q: a horizontal edge colour and a non-edge colour; c: the same seen rolled by 45 degrees.
  const auto q = Values({{Bin(0, 0), 2}, {Bin(2, 5), 3}});
  const auto c = Values({{Bin(0, 0), 2}, {Bin(4, 5), 3}});
  // Unrolled, only the non-edge bin matches: 4 / (13 + 13 - 4).
  EXPECT_DOUBLE_EQ(Tanimoto(q, c), 4.0 / 22.0);
  EXPECT_DOUBLE_EQ(TanimotoRotationTolerant(q, c), 1.0);
  // A roll never lowers the score below the plain coefficient.
  const auto d = Values({{Bin(3, 1), 4}, {Bin(1, 2), 1}});
  EXPECT_GE(TanimotoRotationTolerant(q, d), Tanimoto(q, d));
}

TEST(LireDistance, EdgeCasesByHand) {
  const DescriptorValues zero{};
  EXPECT_DOUBLE_EQ(LireDistance(zero, zero), 0.0);
  EXPECT_DOUBLE_EQ(LireDistance(zero, Values({{7, 1}})), 100.0);
  EXPECT_DOUBLE_EQ(LireDistance(Values({{7, 1}}), zero), 100.0);
  EXPECT_NEAR(LireDistance(Values({{0, 3}, {1, 1}}), Values({{0, 6}, {1, 2}})), 0.0, 1e-12);
  // a' = (1/2, 1/2), b' = (1, 0): a'.b' = 1/2, a'.a' = 1/2, b'.b' = 1 -> 100 - 100 * 0.5 = 50.
  EXPECT_NEAR(LireDistance(Values({{0, 1}, {1, 1}}), Values({{0, 4}})), 50.0, 1e-12);
}

TEST(LireDistance, MatchesLireOnTheConformancePairs) {
  const auto dir = testing::DataDir() / "cedd-conformance";
  std::map<std::string, DescriptorValues> vectors;
  for (const auto& ref : testing::ReadReferenceVectors(dir / "lire-cedd-reference.txt")) {
    vectors[ref.path] = ref.values;
  }
  std::ifstream in(dir / "lire-cedd-distances.txt");
  ASSERT_TRUE(in) << "cannot read lire-cedd-distances.txt";
  std::string line;
  int pairs = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag, a, b;
    double expected = -1;
    fields >> tag >> a >> b >> expected;
    ASSERT_EQ(tag, "DIST") << line;
    ASSERT_TRUE(vectors.count(a) && vectors.count(b)) << line;
    EXPECT_NEAR(LireDistance(vectors[a], vectors[b]), expected, 1e-9) << line;
    ++pairs;
  }
  EXPECT_EQ(pairs, 28);
}

}  // namespace
}  // namespace orbit
