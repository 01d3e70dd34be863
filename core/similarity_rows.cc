#include "core/similarity_rows.h"

#include <cstdint>

#include "core/cpu_dispatch.h"

namespace orbit {

namespace {

// qc[v] = q . c_v and cc[v] = c_v . c_v for `count` descriptors: Tanimoto()'s exact integer
// products, without recomputing q . q for every view, in AVX2 where the CPU has it.
ORBIT_AVX2_CLONES void Products(const std::uint8_t* __restrict q,
                                const std::uint8_t* const* __restrict descriptors,
                                std::size_t count, std::int32_t* __restrict qc,
                                std::int32_t* __restrict cc) {
  for (std::size_t v = 0; v < count; ++v) {
    const std::uint8_t* __restrict c = descriptors[v];
    std::int32_t dot = 0, norm = 0;
    for (int i = 0; i < kDescriptorSize; ++i) {
      dot += q[i] * c[i];
      norm += c[i] * c[i];
    }
    qc[v] = dot;
    cc[v] = norm;
  }
}

}  // namespace

std::vector<float> SimilarityRow(const DescriptorValues& frame, const IndexedObject& object) {
  const std::vector<ModelView>& views = object.model().views;
  const std::size_t count = views.size();
  std::vector<const std::uint8_t*> descriptors(count);
  for (std::size_t v = 0; v < count; ++v) descriptors[v] = views[v].descriptor.data();
  std::vector<std::int32_t> qc(count), cc(count);
  Products(frame.data(), descriptors.data(), count, qc.data(), cc.data());
  std::int32_t qq = 0;
  for (const std::uint8_t value : frame) qq += value * value;
  // As Tanimoto(): 1 for two zero vectors, else q.c / (q.q + c.c - q.c), rounded once.
  std::vector<float> row(count);
  for (std::size_t v = 0; v < count; ++v) {
    row[v] = qq == 0 && cc[v] == 0
                 ? 1.0f
                 : static_cast<float>(static_cast<double>(qc[v]) / (qq + cc[v] - qc[v]));
  }
  return row;
}

void SimilarityRows::Forget(std::span<const IndexedObject* const> objects) {
  for (auto& rows : frames_) {
    for (const IndexedObject* object : objects) rows.erase(object);
  }
}

ObjectRows SimilarityRows::For(std::span<const QueryFrame> window, const IndexedObject& object) {
  ObjectRows rows{&object, {}};
  rows.rows.reserve(window.size());
  for (std::size_t k = 0; k < window.size(); ++k) {
    auto [at, added] = frames_[k].try_emplace(&object);
    if (added) at->second = SimilarityRow(window[k].descriptor.values, object);
    rows.rows.emplace_back(at->second);
  }
  return rows;
}

}  // namespace orbit
