// ViewBins: descriptors kept bin by bin, 4 bits a value; the products a similarity row sums,
// checked against the descriptors' own values for every view count from 1 to 130 (odd, even,
// one and more than one cache line a bin).
#include "core/index/view_bins.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/hand_made_descriptors.h"

namespace orbit {
namespace {

using testing::Bins;

// View v's value in bin d: every value 0..7 appears, and neighbours differ.
std::uint8_t ValueOf(std::size_t view, std::size_t bin) {
  return static_cast<std::uint8_t>((view * 5 + bin * 3 + view * bin) % 8);
}

std::vector<DescriptorValues> Views(std::size_t count) {
  std::vector<DescriptorValues> views(count);
  for (std::size_t v = 0; v < count; ++v) {
    for (std::size_t d = 0; d < kDescriptorSize; ++d) views[v][d] = ValueOf(v, d);
  }
  return views;
}

TEST(ViewBinsTest, EveryValueReadsBackForAnyViewCount) {
  for (std::size_t count = 1; count <= 130; ++count) {
    const ViewBins bins(Views(count));
    ASSERT_EQ(bins.view_count(), count);
    EXPECT_EQ(bins.padded_count(), (count + 1) / 2 * 2);
    for (std::size_t d = 0; d < kDescriptorSize; ++d) {
      for (std::size_t v = 0; v < count; ++v) {
        ASSERT_EQ(bins.Value(d, v), ValueOf(v, d))
            << count << " views, bin " << d << ", view " << v;
      }
    }
  }
}

// The dot product of a query with every view, summed bin by bin as a similarity row does,
// equals the one computed from the descriptors directly.
TEST(ViewBinsTest, ProductsSummedBinByBinAreTheDotProducts) {
  DescriptorValues query{};
  for (std::size_t d = 0; d < kDescriptorSize; ++d) query[d] = static_cast<std::uint8_t>(d % 8);
  for (const std::size_t count : {1u, 2u, 7u, 72u, 129u}) {
    const std::vector<DescriptorValues> views = Views(count);
    const ViewBins bins(views);
    std::vector<std::uint16_t> products(bins.padded_count(), 0);
    for (std::size_t d = 0; d < kDescriptorSize; ++d) {
      if (query[d] != 0) bins.AddProducts(d, query[d], products);
    }
    for (std::size_t v = 0; v < count; ++v) {
      int dot = 0;
      for (std::size_t d = 0; d < kDescriptorSize; ++d) dot += query[d] * views[v][d];
      EXPECT_EQ(products[v], dot) << count << " views, view " << v;
    }
  }
}

// Worked by hand: two views, bin 0 holds 7 and 3; bin 1 holds 0 and 5.
TEST(ViewBinsTest, TwoViewsByHand) {
  const ViewBins bins(std::vector<DescriptorValues>{Bins({{0, 7}}), Bins({{0, 3}, {1, 5}})});
  std::vector<std::uint16_t> products(2, 0);
  bins.AddProducts(0, 2, products);  // 2 x 7, 2 x 3
  EXPECT_EQ(products, (std::vector<std::uint16_t>{14, 6}));
  bins.AddProducts(1, 4, products);  // + 4 x 0, + 4 x 5
  EXPECT_EQ(products, (std::vector<std::uint16_t>{14, 26}));
}

}  // namespace
}  // namespace orbit
