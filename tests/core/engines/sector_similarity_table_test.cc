#include "core/engines/sector_similarity_table.h"

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/index/indexed_object.h"
#include "core/index/view_index.h"
#include "tests/support/coil_models.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

// Query frames for the checks: odd COIL-100 views (not in the even-view models), an empty
// frame (TC 0 with every state), and frames of a single bin (many objects match them alike).
std::vector<DescriptorValues> Queries() {
  std::vector<DescriptorValues> queries;
  for (const int object : {3, 17, 42}) {
    for (const int azimuth : {5, 95, 275}) queries.push_back(testing::CoilView(object, azimuth));
  }
  queries.push_back(DescriptorValues{});
  for (const int bin : {0, 7, 143}) {
    DescriptorValues one_bin{};
    one_bin[bin] = 7;
    queries.push_back(one_bin);
  }
  return queries;
}

// The table's layout is [state * objects + object], and each value is the state mean's
// Tanimoto coefficient with the query, rounded to float.
TEST(SectorSimilarityTableTest, ComputeGivesEachStatesTanimotoWithItsMean) {
  const ViewIndex index(testing::CoilObjects(1, 20, testing::EvenView),
                        {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  const int states = 8;
  const SectorSimilarityTable table(*snapshot, states);
  ASSERT_EQ(table.object_count(), 20u);
  std::vector<float> similarity(20 * states);
  for (const DescriptorValues& query : Queries()) {
    table.Compute(query, similarity);
    for (std::size_t o = 0; o < 20; ++o) {
      const SectorViews& sectors = snapshot->objects()[o].object->Sectors(states);
      for (int i = 0; i < states; ++i) {
        EXPECT_NEAR(similarity[i * 20 + o], Tanimoto(query, sectors.descriptor[i]), 1e-6)
            << "object " << o << ", state " << i;
      }
    }
  }
}

// A session reads back the objects it decodes with ComputeObject: the values must be the
// table's to the last bit, or its decoded paths and scores would depend on which objects it
// happened to keep. Every object, for 1, 5, 8 and 36 states.
TEST(SectorSimilarityTableTest, ComputeObjectGivesTheTablesValuesBitForBit) {
  const ViewIndex index(testing::CoilObjects(1, 30, testing::EvenView),
                        {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  const std::size_t objects = snapshot->object_count();
  for (const int states : {1, 5, 8, 36}) {
    const SectorSimilarityTable table(*snapshot, states);
    std::vector<float> all(objects * states), one(states);
    for (const DescriptorValues& query : Queries()) {
      table.Compute(query, all);
      for (std::size_t o = 0; o < objects; ++o) {
        SectorSimilarityTable::ComputeObject(query, snapshot->objects()[o].object->Sectors(states),
                                             one);
        for (int i = 0; i < states; ++i) {
          ASSERT_EQ(one[i], all[i * objects + o])
              << states << " states, object " << o << ", state " << i;
        }
      }
    }
  }
}

// A sector of more than 4681 views of value 7 overflows the table's 16-bit sums; the table
// computes such states from their mean instead, and ComputeObject must agree.
TEST(SectorSimilarityTableTest, AnOverfullSectorGivesTheSameValuesBothWays) {
  ObjectModel crowded;
  crowded.id = 1;
  for (int v = 0; v < 5000; ++v) {
    ModelView view;
    view.descriptor[v % 3] = 7;
    view.descriptor[10] = static_cast<std::uint8_t>(v % 8);
    view.azimuth = 40.0 * v / 5000;  // all in sector 0 of 8
    crowded.views.push_back(view);
  }
  ObjectModel sparse;
  sparse.id = 2;
  ModelView view;
  view.descriptor[10] = 4;
  view.azimuth = 200;
  sparse.views.push_back(view);
  const ViewIndex index({crowded, sparse}, {.search = SearchMode::kExact});
  const auto snapshot = index.Snapshot();
  const SectorSimilarityTable table(*snapshot, 8);
  const SectorViews& sectors = snapshot->objects()[0].object->Sectors(8);
  ASSERT_GT(sectors.views[0].size(), 4681u);
  DescriptorValues query{};
  query[0] = 7;
  query[10] = 3;
  std::vector<float> all(2 * 8), one(8);
  table.Compute(query, all);
  SectorSimilarityTable::ComputeObject(query, sectors, one);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(one[i], all[i * 2]) << "state " << i;
    EXPECT_NEAR(one[i], Tanimoto(query, sectors.descriptor[i]), 1e-6) << "state " << i;
  }
  // Worked by hand for sector 0: the mean has 7/3 in bins 0-2 and 3.5 in bin 10 (values 0..7
  // equally often), so q.S = 7 x 7/3 + 3 x 3.5 = 26.83, q.q = 58, S.S = 3 x 49/9 + 12.25 =
  // 28.58: TC = 26.83 / (58 + 28.58 - 26.83) = 0.449.
  EXPECT_NEAR(one[0], 0.449, 0.001);
}

TEST(SectorSimilarityTableTest, ComputeObjectRefusesTooSmallASpan) {
  const ViewIndex index(testing::CoilObjects(1, 1, testing::EvenView),
                        {.search = SearchMode::kExact});
  std::vector<float> too_small(7);
  EXPECT_EQ(testing::ErrorMessageOf([&] {
              SectorSimilarityTable::ComputeObject(
                  DescriptorValues{}, index.Snapshot()->objects()[0].object->Sectors(8), too_small);
            }),
            "SectorSimilarityTable: result span too small");
}

}  // namespace
}  // namespace orbit
