#include "core/similarity_rows.h"

#include "core/similarity.h"

namespace orbit {

std::vector<float> SimilarityRow(const DescriptorValues& frame, const IndexedObject& object) {
  std::vector<float> row;
  row.reserve(object.model().views.size());
  for (const ModelView& view : object.model().views) {
    row.push_back(static_cast<float>(Tanimoto(frame, view.descriptor)));
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
