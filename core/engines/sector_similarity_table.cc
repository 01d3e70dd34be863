#include "core/engines/sector_similarity_table.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "core/base/cpu_dispatch.h"

namespace orbit {
namespace {

// A sector's sum of views fits 16 bits while it holds at most this many views (7 each).
constexpr std::size_t kMaxViewsForExactSums = 32767 / kDescriptorMaxValue;

// Rows padded to 16 values (32 bytes) so that every row starts aligned for the vector loop.
constexpr std::size_t kRowAlignment = 16;

// acc[s] += q * row[s]: exact, since |q * row[s]| <= 7 * 32767 and at most 144 such terms are
// added. A hot loop (core/base/cpu_dispatch.h): the AVX2 path handles 8 states per instruction.
ORBIT_HOT_LOOP void AddScaledRow(const std::int16_t* __restrict row, std::int32_t q,
                                 std::int32_t* __restrict acc, std::size_t n) {
  for (std::size_t s = 0; s < n; ++s) acc[s] += q * row[s];
}

// similarity[s] = TC from the dot product with the state's sum: q.S = acc / count, and
// TC = q.S / (q.q + S.S - q.S); 1 when both are zero vectors, 0 when only one is.
ORBIT_HOT_LOOP void TanimotoFromSums(const std::int32_t* __restrict acc,
                                     const float* __restrict inverse_counts,
                                     const float* __restrict squared_norms, float query_norm,
                                     float* __restrict similarity, std::size_t n) {
  for (std::size_t s = 0; s < n; ++s) {
    const float qc = static_cast<float>(acc[s]) * inverse_counts[s];
    const float denominator = query_norm + squared_norms[s] - qc;
    const float both_zero = (query_norm == 0.0f && squared_norms[s] == 0.0f) ? 1.0f : 0.0f;
    similarity[s] = denominator > 0.0f ? qc / denominator : both_zero;
  }
}

// A state's constants as the table stores them and ComputeObject uses them, written once so that
// the two give the same floats: 1 / its views, its mean's S.S, and whether its sums could
// overflow 16 bits (then it is computed from its mean).
float InverseCount(const SectorViews& sectors, std::size_t i) {
  return 1.0f / static_cast<float>(sectors.views[i].size());
}
float SquaredNorm(const SectorViews& sectors, std::size_t i) {
  return static_cast<float>(sectors.squared_norm[i]);
}
bool IsWide(const SectorViews& sectors, std::size_t i) {
  return sectors.views[i].size() > kMaxViewsForExactSums;
}

std::vector<const IndexedObject*> ObjectsOf(const ViewIndexSnapshot& index) {
  std::vector<const IndexedObject*> objects;
  objects.reserve(index.object_count());
  for (const ObjectSlot& slot : index.objects()) objects.push_back(slot.object);
  return objects;
}

}  // namespace

SectorSimilarityTable::SectorSimilarityTable(const ViewIndexSnapshot& index, int states)
    : SectorSimilarityTable(ObjectsOf(index), states) {}

std::shared_ptr<const SectorSimilarityTable> SectorSimilarityTable::Of(
    const ViewIndexSnapshot& index, int states) {
  if (states < 1) throw std::invalid_argument("an HMM needs at least one state");
  return std::static_pointer_cast<const SectorSimilarityTable>(
      index.Derived({kDerivedName, states}, [&]() -> std::shared_ptr<const void> {
        return std::make_shared<const SectorSimilarityTable>(index, states);
      }));
}

SectorSimilarityTable::SectorSimilarityTable(std::span<const IndexedObject* const> objects,
                                             int states)
    : objects_(objects.size()), states_(states) {
  if (states < 1) throw std::invalid_argument("an HMM needs at least one state");
  const std::size_t count = objects_ * static_cast<std::size_t>(states_);
  stride_ = (count + kRowAlignment - 1) / kRowAlignment * kRowAlignment;
  bin_sums_.assign(stride_ * kDescriptorSize, 0);
  inverse_counts_.assign(stride_, 0.0f);
  squared_norms_.assign(stride_, 0.0f);
  // The objects' sums are computed once for their life (IndexedObject::Sectors), so a new
  // snapshot's table costs one write per bin and state. Written in blocks of kBlock states, one
  // bin at a time, so each write fills a cache line of a row instead of touching a new line per
  // value: the first session on a new snapshot builds the table while the others wait for it
  // (docs/results/load.md, "At 1000 objects", measures the gain).
  std::vector<const ViewSum*> sums(count, nullptr);
  for (std::size_t o = 0; o < objects_; ++o) {
    const SectorViews& sectors = objects[o]->Sectors(states_);
    for (std::size_t i = 0; i < static_cast<std::size_t>(states_); ++i) {
      const std::size_t s = i * objects_ + o;
      inverse_counts_[s] = InverseCount(sectors, i);
      squared_norms_[s] = SquaredNorm(sectors, i);
      if (IsWide(sectors, i)) {
        wide_states_.emplace_back(s, &sectors.descriptor[i]);
      } else {
        sums[s] = &sectors.sum[i];
      }
    }
  }
  constexpr std::size_t kBlock = 32;  // int16 values in a 64-byte cache line
  for (std::size_t first = 0; first < count; first += kBlock) {
    const std::size_t last = std::min(count, first + kBlock);
    for (int d = 0; d < kDescriptorSize; ++d) {
      std::int16_t* row = &bin_sums_[static_cast<std::size_t>(d) * stride_];
      for (std::size_t s = first; s < last; ++s) {
        if (sums[s] != nullptr) row[s] = static_cast<std::int16_t>((*sums[s])[d]);
      }
    }
  }
}

void SectorSimilarityTable::Compute(const DescriptorValues& query,
                                    std::span<float> similarity) const {
  const std::size_t count = objects_ * static_cast<std::size_t>(states_);
  if (similarity.size() < count) {
    throw std::invalid_argument("SectorSimilarityTable: result span too small");
  }
  // An empty index has no rows: &bin_sums_[...] below would index an empty vector.
  if (count == 0) return;
  thread_local std::vector<std::int32_t> acc;
  acc.assign(stride_, 0);
  std::int32_t query_norm = 0;
  for (int d = 0; d < kDescriptorSize; ++d) {
    if (query[d] == 0) continue;  // most bins of a CEDD are empty
    query_norm += query[d] * query[d];
    RunHotLoop<AddScaledRow>(&bin_sums_[static_cast<std::size_t>(d) * stride_], query[d],
                             acc.data(), count);
  }
  RunHotLoop<TanimotoFromSums>(acc.data(), inverse_counts_.data(), squared_norms_.data(),
                               static_cast<float>(query_norm), similarity.data(), count);
  for (const auto& [s, mean] : wide_states_) {
    similarity[s] = static_cast<float>(Tanimoto(query, *mean));
  }
}

QueryBins::QueryBins(const DescriptorValues& query) : values(query) {
  for (int d = 0; d < kDescriptorSize; ++d) {
    if (query[d] == 0) continue;
    squared_norm += query[d] * query[d];
    bins[used++] = static_cast<std::uint16_t>(d);
  }
}

void SectorSimilarityTable::ComputeObject(const DescriptorValues& query, const SectorViews& sectors,
                                          std::span<float> similarity) {
  ComputeObject(QueryBins(query), sectors, similarity);
}

void SectorSimilarityTable::ComputeObject(const QueryBins& query, const SectorViews& sectors,
                                          std::span<float> similarity) {
  const std::size_t count = static_cast<std::size_t>(sectors.count);
  if (similarity.size() < count) {
    throw std::invalid_argument("SectorSimilarityTable: result span too small");
  }
  // The same integers as Compute's accumulators (exact, in any order), then the same float
  // steps through the same function: equal results bit for bit. Over the query's non-zero bins
  // only, as Compute.
  thread_local std::vector<std::int32_t> acc;
  thread_local std::vector<float> inverse_counts, squared_norms;
  acc.resize(count);
  inverse_counts.resize(count);
  squared_norms.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const ViewSum& sum = sectors.sum[i];
    std::int32_t dot = 0;
    for (std::size_t k = 0; k < query.used; ++k) {
      dot += query.values[query.bins[k]] * sum[query.bins[k]];
    }
    acc[i] = dot;
    inverse_counts[i] = InverseCount(sectors, i);
    squared_norms[i] = SquaredNorm(sectors, i);
  }
  RunHotLoop<TanimotoFromSums>(acc.data(), inverse_counts.data(), squared_norms.data(),
                               static_cast<float>(query.squared_norm), similarity.data(), count);
  for (std::size_t i = 0; i < count; ++i) {
    if (IsWide(sectors, i)) {
      similarity[i] = static_cast<float>(Tanimoto(query.values, sectors.descriptor[i]));
    }
  }
}

}  // namespace orbit
