// Distractors: generated objects an evaluation adds to its model set only (`orbit eval
// --distractors N`), so that recognition is measured among many other objects while the queries
// stay the dataset's (docs/design.md#distractors). Each is a RandomSyntheticObject
// (evaluation/synthetic_object.h) rendered at kDistractorViews azimuths and described as every
// enrollment describes a view.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/model/object_model.h"

namespace orbit {

inline constexpr int kDistractorViews = 72;  // 5 degrees apart, as COIL-100's
inline constexpr int kMaxDistractors = 100'000;

// `count` distractor models in `variant`, ids first_id, first_id + 1, ..., names
// "distractor<k>" (k from 1), drawn from `seed`, on `threads` threads (0: every CPU);
// `progress(done, count)` after each object (never concurrently; may be empty). The same
// arguments give the same models.
// Throws std::invalid_argument when count is outside 0..kMaxDistractors.
std::vector<ObjectModel> MakeDistractors(int count, DescriptorVariant variant, ObjectId first_id,
                                         std::uint64_t seed, int threads,
                                         const std::function<void(int done, int count)>& progress);

}  // namespace orbit
