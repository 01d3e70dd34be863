#include "evaluation/evaluation_protocol.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/base/angles.h"
#include "core/base/seeded_random.h"

namespace orbit {
namespace {

// Azimuths read from files (e.g. 12.3 in a manifest) may carry rounding; a view exactly 10
// degrees away must still count as "within 10 degrees".
constexpr double kAngleTolerance = 1e-9;

}  // namespace

std::uint64_t TrialSeed(std::uint64_t seed, int object, int n, int trial) {
  std::uint64_t s = MixSeed(seed, static_cast<std::uint64_t>(object));
  s = MixSeed(s, static_cast<std::uint64_t>(n));
  return MixSeed(s, static_cast<std::uint64_t>(trial));
}

std::vector<int> ExcludedViews(std::span<const double> view_azimuths,
                               std::span<const int> query_views) {
  std::vector<int> removed;
  for (int v = 0; v < static_cast<int>(view_azimuths.size()); ++v) {
    const bool near_query = std::any_of(query_views.begin(), query_views.end(), [&](int q) {
      return std::abs(AzimuthChange(view_azimuths[q], view_azimuths[v])) <=
             kQueryExclusionDegrees + kAngleTolerance;
    });
    if (near_query) removed.push_back(v);
  }
  return removed;
}

int NextActiveView(std::span<const double> view_azimuths, int latest, SuggestedMove move,
                   double step, int& direction) {
  if (move == SuggestedMove::kRight) direction = 1;
  if (move == SuggestedMove::kLeft) direction = -1;
  const double target = view_azimuths[latest] + direction * step;
  int nearest = 0;
  for (int v = 1; v < static_cast<int>(view_azimuths.size()); ++v) {
    if (std::abs(AzimuthChange(target, view_azimuths[v])) <
        std::abs(AzimuthChange(target, view_azimuths[nearest]))) {
      nearest = v;
    }
  }
  return nearest;
}

TrialQuery SampleTrial(std::span<const double> view_azimuths, int n, std::uint64_t trial_seed) {
  const int count = static_cast<int>(view_azimuths.size());
  if (n < 1 || n > count) {
    throw std::invalid_argument("SampleTrial: cannot draw " + std::to_string(n) +
                                " distinct views from " + std::to_string(count));
  }
  for (double a : view_azimuths) {
    if (!std::isfinite(a)) throw std::invalid_argument("SampleTrial: azimuth not finite");
  }
  SeededRandom random(trial_seed);

  // n distinct views: the first n steps of a Fisher-Yates shuffle.
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  for (int i = 0; i < n; ++i) {
    const int j = i + static_cast<int>(random.UniformInt(static_cast<std::uint64_t>(count - i)));
    std::swap(order[i], order[j]);
  }
  TrialQuery query;
  query.views.assign(order.begin(), order.begin() + n);
  std::sort(query.views.begin(), query.views.end(), [&](int a, int b) {
    const double za = NormaliseAzimuth(view_azimuths[a]);
    const double zb = NormaliseAzimuth(view_azimuths[b]);
    return za != zb ? za < zb : a < b;
  });

  // Device azimuths: one unknown offset for the whole trial, independent noise per frame.
  const double offset = 360.0 * random.Uniform();
  for (int v : query.views) {
    const double noise = kQueryAzimuthNoiseDegrees * random.Normal();
    query.azimuths.push_back(NormaliseAzimuth(view_azimuths[v] + noise + offset));
  }

  query.removed_views = ExcludedViews(view_azimuths, query.views);
  return query;
}

ObjectModel WithoutViews(const ObjectModel& model, std::span<const int> removed_views) {
  ObjectModel result = model;
  result.views.clear();
  std::size_t next = 0;  // position in removed_views
  const int count = static_cast<int>(model.views.size());
  for (std::size_t i = 0; i < removed_views.size(); ++i) {
    const int v = removed_views[i];
    if (v < 0 || v >= count || (i > 0 && v <= removed_views[i - 1])) {
      throw std::invalid_argument("WithoutViews: view indices must be ascending and in range");
    }
  }
  for (int v = 0; v < count; ++v) {
    if (next < removed_views.size() && removed_views[next] == v) {
      ++next;
      continue;
    }
    result.views.push_back(model.views[v]);
  }
  return result;
}

bool IsTopOneHit(std::span<const RankedObject> ranking, ObjectId expected) {
  return !ranking.empty() && ranking.front().object == expected;
}

}  // namespace orbit
