// Distractors: generated objects an evaluation adds to its model set only (`orbit eval
// --distractors N`), so that recognition is measured among many other objects while the queries
// stay the dataset's, and that `orbit import --layout distractors` enrolls to build a large
// catalogue (docs/design.md#distractors). Each is a RandomSyntheticObject
// (evaluation/synthetic_object.h) rendered at kDistractorViews azimuths and described as every
// enrollment describes a view.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/model/object_model.h"
#include "evaluation/synthetic_object.h"

namespace orbit {

inline constexpr int kDistractorViews = 72;  // 5 degrees apart, as COIL-100's
inline constexpr int kMaxDistractors = 100'000;

// The distractors drawn from one seed. Distractor k (from 1) is named "distractor<k>" and is the
// same object for the same seed whichever others are made, in whatever order. Every box shares
// its geometry with every other box and every cylinder with every cylinder, so the rays of both
// shapes' views are cast once, at construction, and each object only paints them.
// Thread-safe once constructed.
class DistractorObjects {
 public:
  // Casts the rays on `threads` threads (0: every CPU).
  DistractorObjects(std::uint64_t seed, int threads);

  // "distractor<k>".
  static std::string Name(int k);

  // Distractor k's views, described in `variant` with the constructor's seed as the base of
  // the noisy copies' seed rule, on `threads` threads (the numbers do not depend on them).
  // Throws std::invalid_argument when k is outside 1..kMaxDistractors.
  std::vector<ModelView> Views(int k, DescriptorVariant variant, int threads) const;

 private:
  std::uint64_t seed_;
  std::uint64_t objects_seed_;
  std::vector<ViewRays> rays_;  // the box's views, then the cylinder's, by azimuth
};

// `count` distractor models in `variant`, ids first_id, first_id + 1, ..., distractors 1..count
// of `seed` (DistractorObjects), on `threads` threads (0: every CPU); `progress(done, count)`
// after each object (never concurrently; may be empty). The same arguments give the same models.
// Throws std::invalid_argument when count is outside 0..kMaxDistractors.
std::vector<ObjectModel> MakeDistractors(int count, DescriptorVariant variant, ObjectId first_id,
                                         std::uint64_t seed, int threads,
                                         const std::function<void(int done, int count)>& progress);

}  // namespace orbit
