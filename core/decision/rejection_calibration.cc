#include "core/decision/rejection_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/base/angles.h"
#include "core/base/seeded_random.h"
#include "core/decision/unknown_statistic.h"

namespace orbit {
namespace {

// One sampled view against every object of the index: per object, the view's best similarity
// to it and the Ttyp of that best view. Its own object's entry is -1 (never a winner).
struct SampledView {
  std::size_t object = 0;           // position in index.objects()
  std::vector<float> best;          // [objects]
  std::vector<float> best_typical;  // [objects]
  // Its best similarity to its own object's views outside kOwnNeighbourhoodDegrees, and that
  // view's Ttyp; own_best is -1 when the object has no such view.
  float own_best = -1.0f;
  float own_typical = 0.0f;
};

// Which views of each object to sample: `per_object` of them, evenly spread over its views in
// azimuth order.
std::vector<SampledView> SampleViews(const ViewIndexSnapshot& index, int per_object) {
  const std::vector<ObjectSlot>& objects = index.objects();
  std::vector<SampledView> sampled;
  std::vector<float> similarities;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    const IndexedObject& object = *objects[o].object;
    const std::vector<int>& by_azimuth = object.views_by_azimuth();
    const int count = std::min<int>(per_object, static_cast<int>(by_azimuth.size()));
    for (int i = 0; i < count; ++i) {
      const int view = by_azimuth[static_cast<std::size_t>(i) * by_azimuth.size() / count];
      index.SimilarityToEveryView(object.model().views[view].descriptor, similarities);
      SampledView sample{o, std::vector<float>(objects.size(), -1.0f),
                         std::vector<float>(objects.size(), 0.0f)};
      const double azimuth = object.model().views[view].azimuth;
      for (int v = 0; v < object.view_count(); ++v) {
        const float similarity = similarities[objects[o].first_slot + v];
        if (std::abs(AzimuthChange(azimuth, object.model().views[v].azimuth)) >
                kOwnNeighbourhoodDegrees &&
            similarity > sample.own_best) {
          sample.own_best = similarity;
          sample.own_typical = static_cast<float>(object.model().views[v].typical_distance);
        }
      }
      for (std::size_t p = 0; p < objects.size(); ++p) {
        if (p == o) continue;
        const IndexedObject& other = *objects[p].object;
        for (int v = 0; v < other.view_count(); ++v) {
          const float similarity = similarities[objects[p].first_slot + v];
          if (similarity > sample.best[p]) {
            sample.best[p] = similarity;
            sample.best_typical[p] = static_cast<float>(other.model().views[v].typical_distance);
          }
        }
      }
      sampled.push_back(std::move(sample));
    }
  }
  return sampled;
}

// Per object, the summed best similarity of the frames `frames` to it, into `sums`.
void SumBest(const std::vector<SampledView>& sampled, const std::vector<int>& frames,
             std::vector<double>& sums) {
  std::fill(sums.begin(), sums.end(), 0.0);
  for (const int f : frames) {
    const std::vector<float>& best = sampled[f].best;
    for (std::size_t p = 0; p < sums.size(); ++p) sums[p] += best[p];
  }
}

// U of one simulated window: the frames `frames` (sampled views of one object) answered by the
// two other objects with the largest summed similarity.
double WindowStatistic(const std::vector<SampledView>& sampled, const std::vector<int>& frames,
                       std::vector<double>& sums) {
  SumBest(sampled, frames, sums);
  std::size_t winner = 0, runner_up = sums.size();
  for (std::size_t p = 1; p < sums.size(); ++p) {
    if (sums[p] > sums[winner]) winner = p;
  }
  for (std::size_t p = 0; p < sums.size(); ++p) {
    if (p == winner || sampled[frames[0]].best[p] < 0) continue;
    if (runner_up == sums.size() || sums[p] > sums[runner_up]) runner_up = p;
  }
  double d1 = 0, d2 = 0, typical = 0;
  for (const int f : frames) {
    d1 += 1 - sampled[f].best[winner];
    typical += sampled[f].best_typical[winner];
    d2 += runner_up < sums.size() ? 1 - sampled[f].best[runner_up] : 1.0;
  }
  return UnknownStatisticOf(d1, d2, typical);
}

// U of one simulated window of a known object: the frames `frames` (sampled views of one object
// that have an own view outside their neighbourhood) answered by their own object, against the
// other object with the largest summed similarity.
double KnownWindowStatistic(const std::vector<SampledView>& sampled, const std::vector<int>& frames,
                            std::vector<double>& sums) {
  SumBest(sampled, frames, sums);
  const std::size_t own = sampled[frames[0]].object;
  std::size_t runner_up = sums.size();
  for (std::size_t p = 0; p < sums.size(); ++p) {
    if (p == own) continue;
    if (runner_up == sums.size() || sums[p] > sums[runner_up]) runner_up = p;
  }
  double d1 = 0, d2 = 0, typical = 0;
  for (const int f : frames) {
    d1 += 1 - sampled[f].own_best;
    typical += sampled[f].own_typical;
    d2 += runner_up < sums.size() ? 1 - sampled[f].best[runner_up] : 1.0;
  }
  return UnknownStatisticOf(d1, d2, typical);
}

// The largest value of the sorted `values` with at most `share` of them at or below it (ties
// count whole: a value drawn several times is either all in or all out); just below the least
// value when even that one is too many.
double LowerQuantile(const std::vector<double>& values, double share) {
  const auto allowed = static_cast<std::ptrdiff_t>(share * static_cast<double>(values.size()));
  auto end = std::upper_bound(values.begin(), values.end(),
                              values[std::max<std::ptrdiff_t>(allowed, 1) - 1]);
  while (end - values.begin() > allowed && end != values.begin()) {
    end = std::lower_bound(values.begin(), end, *(end - 1));  // drop the last value and its ties
  }
  return end == values.begin() ? values.front() - 1e-12 : *(end - 1);
}

}  // namespace

RejectionCalibration RejectionCalibration::FromIndex(const ViewIndexSnapshot& index,
                                                     const CalibrationOptions& options) {
  if (options.max_sampled_views < 1 || options.windows_per_length < 1) {
    throw std::invalid_argument(
        "calibration needs max_sampled_views >= 1 and windows_per_length >= 1");
  }
  RejectionCalibration calibration;
  const std::size_t objects = index.object_count();
  if (objects < 2) return calibration;
  const int per_object =
      std::max(1, options.max_sampled_views /
                      static_cast<int>(std::min<std::size_t>(objects, options.max_sampled_views)));
  const std::vector<SampledView> sampled = SampleViews(index, per_object);

  // The sampled views of each object, by position in `sampled`.
  // The sampled views of each object, and those of them with an own view outside their
  // neighbourhood, by position in `sampled`.
  std::vector<std::vector<int>> of_object(objects);
  std::vector<std::vector<int>> matched_of_object(objects);
  for (std::size_t i = 0; i < sampled.size(); ++i) {
    of_object[sampled[i].object].push_back(static_cast<int>(i));
    if (sampled[i].own_best >= 0)
      matched_of_object[sampled[i].object].push_back(static_cast<int>(i));
  }
  std::vector<std::size_t> matched_objects;
  for (std::size_t o = 0; o < objects; ++o) {
    if (!matched_of_object[o].empty()) matched_objects.push_back(o);
  }
  calibration.sampled_objects_ = static_cast<int>(objects);
  calibration.sampled_views_ = static_cast<int>(sampled.size());

  SeededRandom random(options.seed);
  std::vector<double> sums(objects);
  std::vector<int> frames;
  calibration.null_.resize(kCalibratedWindowLengths);
  for (int n = 1; n <= kCalibratedWindowLengths; ++n) {
    std::vector<double>& null = calibration.null_[n - 1];
    null.reserve(options.windows_per_length);
    for (int w = 0; w < options.windows_per_length; ++w) {
      const std::vector<int>& pool = of_object[random.UniformInt(objects)];
      frames.clear();
      for (int k = 0; k < n; ++k) frames.push_back(pool[random.UniformInt(pool.size())]);
      null.push_back(WindowStatistic(sampled, frames, sums));
    }
    std::sort(null.begin(), null.end());
  }
  if (matched_objects.empty()) return calibration;
  calibration.known_.resize(kCalibratedWindowLengths);
  for (int n = 1; n <= kCalibratedWindowLengths; ++n) {
    std::vector<double>& known = calibration.known_[n - 1];
    known.reserve(options.windows_per_length);
    for (int w = 0; w < options.windows_per_length; ++w) {
      const std::vector<int>& pool =
          matched_of_object[matched_objects[random.UniformInt(matched_objects.size())]];
      frames.clear();
      for (int k = 0; k < n; ++k) frames.push_back(pool[random.UniformInt(pool.size())]);
      known.push_back(KnownWindowStatistic(sampled, frames, sums));
    }
    std::sort(known.begin(), known.end());
  }
  return calibration;
}

const std::vector<double>& RejectionCalibration::Null(int frames) const {
  return null_[static_cast<std::size_t>(std::clamp(frames, 1, kCalibratedWindowLengths) - 1)];
}

const std::vector<double>& RejectionCalibration::Known(int frames) const {
  return known_[static_cast<std::size_t>(std::clamp(frames, 1, kCalibratedWindowLengths) - 1)];
}

double RejectionCalibration::NullThreshold(int frames, double false_accept_rate) const {
  return LowerQuantile(Null(frames), false_accept_rate);
}

double RejectionCalibration::KnownCeiling(int frames) const {
  if (known_.empty()) return std::numeric_limits<double>::infinity();
  const std::vector<double>& known = Known(frames);
  return kKnownCeilingMargin *
         known[std::min(
             known.size() - 1,
             static_cast<std::size_t>(kKnownWindowsAccepted * static_cast<double>(known.size())))];
}

double RejectionCalibration::KnownAcceptRate(double statistic, int frames) const {
  if (known_.empty()) return 1;
  const std::vector<double>& known = Known(frames);
  return static_cast<double>(std::upper_bound(known.begin(), known.end(), statistic) -
                             known.begin()) /
         static_cast<double>(known.size());
}

double RejectionCalibration::FalseAcceptRate(double statistic, int frames) const {
  const std::vector<double>& null = Null(frames);
  const auto at_or_below = std::upper_bound(null.begin(), null.end(), statistic) - null.begin();
  return (static_cast<double>(at_or_below) + 1) / (static_cast<double>(null.size()) + 1);
}

}  // namespace orbit
