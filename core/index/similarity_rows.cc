#include "core/index/similarity_rows.h"

#include <algorithm>
#include <cstdint>

namespace orbit {
namespace {

// TC of a frame with the blend m = (a + b) / 2 of two views: q.m / (q.q + m.m - q.m), every
// term times 4 to stay in integers, from `products` = 2 (q.a + q.b), `qq` = q.q and
// `sum_squared_norm` = |a + b|^2. The denominator is |2q - (a + b)|^2 + 2 q.(a + b): 0 only
// when q and a + b are both 0.
double BlendTanimoto(std::int32_t products, std::int32_t qq, std::int32_t sum_squared_norm) {
  const std::int32_t denominator = 4 * qq + sum_squared_norm - products;
  return denominator == 0 ? 1.0 : static_cast<double>(products) / denominator;
}

}  // namespace

std::vector<float> SimilarityRow(const DescriptorValues& frame, const IndexedObject& object,
                                 float* best_blend, std::vector<float>* blends) {
  const std::vector<std::int32_t>& cc = object.squared_norms();
  const std::size_t count = cc.size();
  // The thread's scratch: a session's answer computes a few of these rows per frame. The
  // products bin by bin (IndexedObject::view_bins), over the frame's non-zero bins only,
  // summed in 16 bits, exactly: values are at most 7, so q . c_v is at most 144 x 49 = 7056.
  static_assert(kDescriptorSize * 7 * 7 <= 0xFFFF);
  thread_local std::vector<std::uint16_t> qc;
  qc.assign(object.view_bins().padded_count(), 0);
  std::int32_t qq = 0;
  for (std::size_t d = 0; d < kDescriptorSize; ++d) {
    if (frame[d] == 0) continue;
    qq += frame[d] * frame[d];
    object.view_bins().AddProducts(d, frame[d], qc);
  }
  // As Tanimoto(): 1 for two zero vectors, else q.c / (q.q + c.c - q.c), rounded once.
  std::vector<float> row(count);
  for (std::size_t v = 0; v < count; ++v) {
    row[v] = qq == 0 && cc[v] == 0
                 ? 1.0f
                 : static_cast<float>(static_cast<double>(qc[v]) / (qq + cc[v] - qc[v]));
  }
  if (best_blend != nullptr || blends != nullptr) {
    double best = 0;
    if (blends != nullptr) blends->clear();
    for (const NeighbourPair& pair : object.neighbour_pairs()) {
      const double blend =
          BlendTanimoto(2 * (qc[pair.first] + qc[pair.second]), qq, pair.sum_squared_norm);
      best = std::max(best, blend);
      if (blends != nullptr) blends->push_back(static_cast<float>(blend));
    }
    if (best_blend != nullptr) *best_blend = static_cast<float>(best);
  }
  return row;
}

void Prefetch(const ObjectRows& rows) {
  constexpr std::size_t kLineFloats = 64 / sizeof(float);
  for (const std::span<const float> row : rows.rows) {
    for (std::size_t v = 0; v < row.size(); v += kLineFloats) __builtin_prefetch(&row[v]);
  }
}

void SimilarityRows::Forget(std::span<const IndexedObject* const> objects) {
  for (std::vector<Row>& rows : frames_) {
    std::erase_if(rows, [&](const Row& row) {
      return std::find(objects.begin(), objects.end(), row.object) != objects.end();
    });
  }
}

ObjectRows SimilarityRows::For(std::span<const QueryFrame> window, const IndexedObject& object) {
  ObjectRows rows{&object, {}, {}};
  rows.rows.reserve(window.size());
  rows.nearest.reserve(window.size());
  for (std::size_t k = 0; k < window.size(); ++k) {
    std::vector<Row>& frame = frames_[k];
    auto at = std::find_if(frame.begin(), frame.end(),
                           [&](const Row& row) { return row.object == &object; });
    if (at == frame.end()) {
      float blended = 0;
      Row row{&object, {}, SimilarityRow(window[k].descriptor.values, object, &blended)};
      const auto highest = std::max_element(row.values.begin(), row.values.end());
      row.nearest = {static_cast<int>(highest - row.values.begin()), *highest, blended};
      frame.push_back(std::move(row));  // moving a Row keeps its values where they are
      at = frame.end() - 1;
    }
    rows.rows.emplace_back(at->values);
    rows.nearest.push_back(at->nearest);
  }
  return rows;
}

}  // namespace orbit
