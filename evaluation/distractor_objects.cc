#include "evaluation/distractor_objects.h"

#include <stdexcept>

#include "core/base/parallel_for.h"
#include "core/base/seeded_random.h"
#include "core/descriptor/view_description.h"

namespace orbit {
namespace {

double Azimuth(std::size_t view) { return static_cast<double>(view) * 360.0 / kDistractorViews; }

constexpr SyntheticObject::Shape kShapes[] = {SyntheticObject::Shape::kBox,
                                              SyntheticObject::Shape::kCylinder};

int Threads(int threads) { return threads > 0 ? threads : AvailableCpus(); }

}  // namespace

DistractorObjects::DistractorObjects(std::uint64_t seed, int threads)
    : seed_(seed),
      objects_seed_(MixSeed(seed, 0x6469737472ULL /* "distr" */)),
      rays_(std::size(kShapes) * kDistractorViews) {
  ParallelFor(rays_.size(), Threads(threads), [&](std::size_t k) {
    rays_[k] = CastViewRays(kShapes[k / kDistractorViews], Azimuth(k % kDistractorViews));
  });
}

std::string DistractorObjects::Name(int k) { return "distractor" + std::to_string(k); }

std::vector<ModelView> DistractorObjects::Views(int k, DescriptorVariant variant,
                                                int threads) const {
  if (k < 1 || k > kMaxDistractors) {
    throw std::invalid_argument("distractor numbers are 1.." + std::to_string(kMaxDistractors) +
                                ", got " + std::to_string(k));
  }
  const SyntheticObject object =
      RandomSyntheticObject(MixSeed(objects_seed_, static_cast<std::uint64_t>(k - 1)), Name(k));
  const std::size_t first = object.shape == SyntheticObject::Shape::kBox ? 0 : kDistractorViews;
  std::vector<ModelView> views(kDistractorViews);
  ParallelFor(views.size(), Threads(threads), [&](std::size_t v) {
    const ViewDescription description =
        DescribeView(RenderView(object, rays_[first + v]), variant, seed_);
    views[v] = {description.descriptor, Azimuth(v), {}, description.typical_distance};
  });
  return views;
}

std::vector<ObjectModel> MakeDistractors(int count, DescriptorVariant variant, ObjectId first_id,
                                         std::uint64_t seed, int threads,
                                         const std::function<void(int done, int count)>& progress) {
  if (count < 0 || count > kMaxDistractors) {
    throw std::invalid_argument("distractors must be in 0.." + std::to_string(kMaxDistractors) +
                                ", got " + std::to_string(count));
  }
  std::vector<ObjectModel> models(static_cast<std::size_t>(count));
  if (count == 0) return models;
  const DistractorObjects distractors(seed, threads);
  ParallelFor(
      models.size(), Threads(threads),
      [&](std::size_t i) {
        const int k = static_cast<int>(i) + 1;
        models[i] = {first_id + static_cast<ObjectId>(i), DistractorObjects::Name(k), variant,
                     distractors.Views(k, variant, 1)};
      },
      [&](std::size_t done) {
        if (progress) progress(static_cast<int>(done), count);
      });
  return models;
}

}  // namespace orbit
