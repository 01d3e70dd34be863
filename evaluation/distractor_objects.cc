#include "evaluation/distractor_objects.h"

#include <stdexcept>
#include <string>

#include "core/base/parallel_for.h"
#include "core/base/seeded_random.h"
#include "core/descriptor/view_description.h"
#include "evaluation/synthetic_object.h"

namespace orbit {

std::vector<ObjectModel> MakeDistractors(int count, DescriptorVariant variant, ObjectId first_id,
                                         std::uint64_t seed, int threads,
                                         const std::function<void(int done, int count)>& progress) {
  if (count < 0 || count > kMaxDistractors) {
    throw std::invalid_argument("distractors must be in 0.." + std::to_string(kMaxDistractors) +
                                ", got " + std::to_string(count));
  }
  const std::uint64_t objects_seed = MixSeed(seed, 0x6469737472ULL /* "distr" */);
  std::vector<ObjectModel> models(static_cast<std::size_t>(count));
  const auto on_done = [&](std::size_t done) {
    if (progress) progress(static_cast<int>(done), count);
  };
  ParallelFor(
      models.size(), threads > 0 ? threads : AvailableCpus(),
      [&](std::size_t k) {
        const std::string name = "distractor" + std::to_string(k + 1);
        const SyntheticObject object = RandomSyntheticObject(MixSeed(objects_seed, k), name);
        ObjectModel& model = models[k];
        model.id = first_id + static_cast<ObjectId>(k);
        model.name = name;
        model.variant = variant;
        for (int v = 0; v < kDistractorViews; ++v) {
          const double azimuth = v * 360.0 / kDistractorViews;
          const ViewDescription description =
              DescribeView(RenderView(object, azimuth), variant, seed);
          model.views.push_back(
              {description.descriptor, azimuth, {}, description.typical_distance});
        }
      },
      on_done);
  return models;
}

}  // namespace orbit
