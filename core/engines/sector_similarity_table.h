// SectorSimilarityTable: TC(S, o) between one query frame and every HMM state of every object
// of a view index at once (docs/design.md#orientation-hmm: the state descriptor S is the mean
// CEDD of the model views in a sector, and the emissions are built from these similarities).
//
// Why a table: an HMM session scores every state of every object on every frame, 8000 states
// for 1000 objects. A state's descriptor is a mean, so S.o = (sum of its views).o / count, an
// exact integer dot product with the sector's sum. The sums are stored bin-major ([bin][state]),
// so a frame costs one multiply-add pass over the states per NON-ZERO bin of the query (a
// COIL-100 CEDD has about 21 of 144), vectorised across states.
//
// Layout of the result: similarity[state * object_count + object], state-major, the layout
// BatchViterbi reads (objects in SIMD lanes). Objects are in the index snapshot's order.
//
// Sharing: a table holds 2 bytes per bin, state and object (2.3 MB for 1000 objects of 8
// states), so the sessions on one index snapshot share one (Of), built by the first of them.
//
// Thread safety: immutable after construction; Compute may be called from many threads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/index/indexed_object.h"
#include "core/index/view_index.h"

namespace orbit {

// A query's non-zero bins, found once per frame for the objects scored one by one
// (SectorSimilarityTable::ComputeObject): a COIL-100 CEDD has about 21 of 144.
struct QueryBins {
  explicit QueryBins(const DescriptorValues& query);
  DescriptorValues values{};
  std::array<std::uint16_t, kDescriptorSize> bins{};  // [0, used): the non-zero bins, ascending
  std::size_t used = 0;
  std::int32_t squared_norm = 0;
};

class SectorSimilarityTable {
 public:
  // The states of every object of `index`, `states` equal sectors each (IndexedObject::Sectors).
  // Throws std::invalid_argument when states < 1.
  SectorSimilarityTable(const ViewIndexSnapshot& index, int states);
  // The states of `objects`, in this order (an HMM session's objects added by an enrollment).
  SectorSimilarityTable(std::span<const IndexedObject* const> objects, int states);

  // The table of `index` for `states`, shared by every caller with the same snapshot
  // (ViewIndexSnapshot::Derived, key {kDerivedName, states}). Throws as the constructor.
  static std::shared_ptr<const SectorSimilarityTable> Of(const ViewIndexSnapshot& index,
                                                         int states);
  static constexpr std::string_view kDerivedName = "sector-similarity-table";

  std::size_t object_count() const { return objects_; }
  int states() const { return states_; }

  // similarity[state * object_count() + object] = TC(S, query) with Tanimoto()'s conventions
  // for zero vectors, rounded to float. `similarity` must hold states() * object_count() values.
  void Compute(const DescriptorValues& query, std::span<float> similarity) const;

  // similarity[i] = TC(S_i, query) for the sectors of one object, to the last bit what Compute
  // gives for that object in any table holding it: an HMM session reads back the few objects it
  // decodes this way instead of keeping every object's similarities for every frame. Computed
  // from the object's own sums (IndexedObject::Sectors), so it needs no table. Throws
  // std::invalid_argument when `similarity` holds fewer than sectors.count values.
  static void ComputeObject(const DescriptorValues& query, const SectorViews& sectors,
                            std::span<float> similarity);
  // The same, for a query whose bins were found already.
  static void ComputeObject(const QueryBins& query, const SectorViews& sectors,
                            std::span<float> similarity);

 private:
  std::size_t objects_ = 0;
  int states_ = 0;
  std::size_t stride_ = 0;              // states * objects, rounded up for aligned rows
  std::vector<std::int16_t> bin_sums_;  // [bin][state * objects + object]: sum of its views
  std::vector<float> inverse_counts_;   // 1 / number of views in the state
  std::vector<float> squared_norms_;    // S.S of the mean
  // States whose sums could overflow 16 bits (over 4681 views in one sector): computed
  // directly from their mean, (position in the result, mean).
  std::vector<std::pair<std::size_t, const MeanDescriptor*>> wide_states_;
};

}  // namespace orbit
