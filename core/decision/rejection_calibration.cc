#include "core/decision/rejection_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include "core/base/angles.h"
#include "core/base/parallel_for.h"
#include "core/base/seeded_random.h"
#include "core/decision/unknown_statistic.h"
#include "core/index/similarity_rows.h"

namespace orbit {
namespace {

// One sampled view against the objects its left-out object is compared with (its columns: every
// object of the index, or its candidates in a large one): per column, the view's best similarity
// to that object (its views and their blends) and the Ttyp of its best view. Its own object is
// never a column.
struct SampledView {
  std::size_t left_out = 0;         // position in the left-out objects
  std::vector<float> best;          // [columns]
  std::vector<float> best_typical;  // [columns]
  // Its best similarity to its own object's views outside kOwnNeighbourhoodDegrees and their
  // blends (MatchOwnViews), and the best view's Ttyp; own_best is -1 when the object has no
  // such view.
  float own_best = -1.0f;
  float own_typical = 0.0f;
};

// An object that plays an unknown one, and its sampled views (positions in the sampled views).
struct LeftOutObject {
  std::size_t position = 0;  // in index.objects()
  std::vector<int> views;
};

// The objects that play unknown ones: every object, or `max_sampled_views` of them spread evenly
// over the index's order when it holds more; each with `per_object` views.
std::vector<LeftOutObject> LeftOutObjects(const ViewIndexSnapshot& index, int max_sampled_views,
                                          int per_object) {
  const std::size_t objects = index.object_count();
  const std::size_t count = std::min<std::size_t>(objects, max_sampled_views);
  std::vector<LeftOutObject> left_out(count);
  int next = 0;
  for (std::size_t i = 0; i < count; ++i) {
    left_out[i].position = i * objects / count;
    const int views =
        std::min<int>(per_object, index.objects()[left_out[i].position].object->view_count());
    for (int k = 0; k < views; ++k) left_out[i].views.push_back(next++);
  }
  return left_out;
}

// The views of `object` to sample: `count` of them, evenly spread over its views in azimuth
// order.
int SampledViewOf(const IndexedObject& object, int count, int k) {
  const std::vector<int>& by_azimuth = object.views_by_azimuth();
  return by_azimuth[static_cast<std::size_t>(k) * by_azimuth.size() / count];
}

// The sampled view's best similarity to its own object's views outside its neighbourhood and to
// the blends of the object's neighbouring pairs outside it (docs/design.md#blended-views), from
// its SimilarityRow with the object: `row` and the pairs' `blends`. Not the pair of views
// either side of the neighbourhood: the object holds no such pair, and their blend would stand
// in for the very view the neighbourhood takes out. own_typical is the Ttyp of the best view,
// as a session reads it.
void MatchOwnViews(const IndexedObject& object, int view, std::span<const float> row,
                   std::span<const float> blends, SampledView& sample) {
  const std::vector<ModelView>& views = object.model().views;
  const double azimuth = views[static_cast<std::size_t>(view)].azimuth;
  const auto outside = [&](int v) {
    return std::abs(AzimuthChange(azimuth, views[static_cast<std::size_t>(v)].azimuth)) >
           kOwnNeighbourhoodDegrees;
  };
  for (int v = 0; v < object.view_count(); ++v) {
    const float value = row[static_cast<std::size_t>(v)];
    if (outside(v) && value > sample.own_best) {
      sample.own_best = value;
      sample.own_typical = static_cast<float>(views[static_cast<std::size_t>(v)].typical_distance);
    }
  }
  const std::vector<NeighbourPair>& pairs = object.neighbour_pairs();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (outside(pairs[i].first) && outside(pairs[i].second))
      sample.own_best = std::max(sample.own_best, blends[i]);
  }
}

// The sampled views of `left_out` against `columns` (positions in index.objects(), its own
// object not among them), each scored exactly as a session's rows score it: per column, the
// view's best similarity to that object's views and their blends, and the Ttyp of its best view.
void CompareWithColumns(const ViewIndexSnapshot& index, const LeftOutObject& left_out,
                        const std::vector<std::size_t>& columns,
                        std::vector<SampledView>& sampled) {
  const std::vector<ObjectSlot>& objects = index.objects();
  const IndexedObject& object = *objects[left_out.position].object;
  const int count = static_cast<int>(left_out.views.size());
  for (int k = 0; k < count; ++k) {
    const int view = SampledViewOf(object, count, k);
    const DescriptorValues& query = object.model().views[static_cast<std::size_t>(view)].descriptor;
    SampledView& sample = sampled[left_out.views[k]];
    sample.best.assign(columns.size(), -1.0f);
    sample.best_typical.assign(columns.size(), 0.0f);
    std::vector<float> blends;
    const std::vector<float> own = SimilarityRow(query, object, nullptr, &blends);
    MatchOwnViews(object, view, own, blends, sample);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const IndexedObject& column = *objects[columns[c]].object;
      float blended = 0;
      const std::vector<float> row = SimilarityRow(query, column, &blended);
      for (std::size_t v = 0; v < row.size(); ++v) {
        if (row[v] > sample.best[c]) {
          sample.best[c] = row[v];
          sample.best_typical[c] = static_cast<float>(column.model().views[v].typical_distance);
        }
      }
      sample.best[c] = std::max(sample.best[c], blended);
    }
  }
}

// Every other object of the index as the columns.
void CompareWithEveryObject(const ViewIndexSnapshot& index, const LeftOutObject& left_out,
                            std::vector<SampledView>& sampled) {
  std::vector<std::size_t> columns;
  for (std::size_t p = 0; p < index.objects().size(); ++p) {
    if (p != left_out.position) columns.push_back(p);
  }
  CompareWithColumns(index, left_out, columns, sampled);
}

// The candidates of the object's sampled views as the columns (the objects ObjectCandidates
// proposes for any of them, the object itself left out).
void CompareWithCandidates(const ViewIndexSnapshot& index, const LeftOutObject& left_out,
                           std::vector<SampledView>& sampled) {
  const IndexedObject& object = *index.objects()[left_out.position].object;
  const int count = static_cast<int>(left_out.views.size());
  std::vector<std::size_t> columns;
  for (int k = 0; k < count; ++k) {
    const int view = SampledViewOf(object, count, k);
    for (const ObjectCandidate& candidate :
         index.ObjectCandidates(object.model().views[static_cast<std::size_t>(view)].descriptor,
                                kLeftOutCandidatesPerView + 1)) {
      if (candidate.position != left_out.position) columns.push_back(candidate.position);
    }
  }
  std::sort(columns.begin(), columns.end());
  columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
  CompareWithColumns(index, left_out, columns, sampled);
}

// The sampled views of every left-out object, compared with their columns on `options.threads`
// threads.
std::vector<SampledView> SampleViews(const ViewIndexSnapshot& index,
                                     const std::vector<LeftOutObject>& left_out,
                                     const CalibrationOptions& options) {
  std::vector<SampledView> sampled;
  for (std::size_t i = 0; i < left_out.size(); ++i) {
    for (std::size_t k = 0; k < left_out[i].views.size(); ++k) sampled.push_back({i, {}, {}});
  }
  const bool candidates = index.object_count() > options.scan_every_object_up_to;
  ParallelFor(left_out.size(), options.threads, [&](std::size_t i) {
    if (candidates) {
      CompareWithCandidates(index, left_out[i], sampled);
    } else {
      CompareWithEveryObject(index, left_out[i], sampled);
    }
  });
  return sampled;
}

// Per column, the summed best similarity of the frames `frames` (sampled views of one object) to
// it, into `sums`.
void SumBest(const std::vector<SampledView>& sampled, const std::vector<int>& frames,
             std::vector<double>& sums) {
  sums.assign(sampled[frames[0]].best.size(), 0.0);
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
    if (p == winner) continue;
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
  std::size_t runner_up = sums.size();
  for (std::size_t p = 0; p < sums.size(); ++p) {
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

// A null window: its U and the left-out object it was drawn from.
struct NullWindow {
  double statistic = 0;
  std::size_t object = 0;
};

// The upper confidence bound of the null's share at each of `windows` (sorted by statistic): the
// mean over the null's objects of each one's share of its own windows at or below the value, plus
// kNullShareBoundSigmas standard errors of that mean; then made non-decreasing. Tied values get
// the bound at the last of them. One pass: each window moves its object's share by one step.
std::vector<double> NullShareBounds(const std::vector<NullWindow>& windows, std::size_t objects) {
  std::vector<int> drawn(objects, 0), below(objects, 0);
  for (const NullWindow& w : windows) ++drawn[w.object];
  const double k = static_cast<double>(
      std::count_if(drawn.begin(), drawn.end(), [](int count) { return count > 0; }));
  std::vector<double> bounds(windows.size());
  double sum = 0, sum_of_squares = 0;  // of the objects' shares
  double running_max = 0;
  std::size_t group_start = 0;
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const std::size_t o = windows[i].object;
    const double before = static_cast<double>(below[o]) / drawn[o];
    const double after = static_cast<double>(++below[o]) / drawn[o];
    sum += after - before;
    sum_of_squares += after * after - before * before;
    if (i + 1 < windows.size() && windows[i + 1].statistic == windows[i].statistic) continue;
    const double mean = sum / k;
    const double variance =
        k > 1 ? std::max(0.0, (sum_of_squares - k * mean * mean) / (k - 1)) : 0.0;
    running_max = std::max(running_max, mean + kNullShareBoundSigmas * std::sqrt(variance / k));
    std::fill(bounds.begin() + static_cast<std::ptrdiff_t>(group_start),
              bounds.begin() + static_cast<std::ptrdiff_t>(i + 1), running_max);
    group_start = i + 1;
  }
  return bounds;
}

}  // namespace

RejectionCalibration RejectionCalibration::FromIndex(const ViewIndexSnapshot& index,
                                                     const CalibrationOptions& options) {
  if (options.max_sampled_views < 1 || options.windows_per_length < 1 || options.threads < 1) {
    throw std::invalid_argument(
        "calibration needs max_sampled_views >= 1, windows_per_length >= 1 and threads >= 1");
  }
  RejectionCalibration calibration;
  const std::size_t objects = index.object_count();
  if (objects < 2) return calibration;
  const int per_object =
      std::max(1, options.max_sampled_views /
                      static_cast<int>(std::min<std::size_t>(objects, options.max_sampled_views)));
  const std::vector<LeftOutObject> left_out =
      LeftOutObjects(index, options.max_sampled_views, per_object);
  const std::vector<SampledView> sampled = SampleViews(index, left_out, options);

  // The sampled views of each left-out object with an own view outside their neighbourhood.
  std::vector<std::vector<int>> matched_of_object(left_out.size());
  for (std::size_t i = 0; i < sampled.size(); ++i) {
    if (sampled[i].own_best >= 0)
      matched_of_object[sampled[i].left_out].push_back(static_cast<int>(i));
  }
  std::vector<std::size_t> matched_objects;
  for (std::size_t o = 0; o < left_out.size(); ++o) {
    if (!matched_of_object[o].empty()) matched_objects.push_back(o);
  }
  calibration.sampled_objects_ = static_cast<int>(left_out.size());
  calibration.sampled_views_ = static_cast<int>(sampled.size());

  SeededRandom random(options.seed);
  std::vector<double> sums;
  std::vector<int> frames;
  calibration.null_.resize(kCalibratedWindowLengths);
  calibration.null_bound_.resize(kCalibratedWindowLengths);
  std::vector<NullWindow> windows;
  for (int n = 1; n <= kCalibratedWindowLengths; ++n) {
    windows.clear();
    for (int w = 0; w < options.windows_per_length; ++w) {
      const std::size_t object = random.UniformInt(left_out.size());
      const std::vector<int>& pool = left_out[object].views;
      frames.clear();
      for (int k = 0; k < n; ++k) frames.push_back(pool[random.UniformInt(pool.size())]);
      windows.push_back({WindowStatistic(sampled, frames, sums), object});
    }
    std::sort(windows.begin(), windows.end(),
              [](const NullWindow& a, const NullWindow& b) { return a.statistic < b.statistic; });
    std::vector<double>& null = calibration.null_[n - 1];
    for (const NullWindow& w : windows) null.push_back(w.statistic);
    calibration.null_bound_[n - 1] = NullShareBounds(windows, left_out.size());
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

const std::vector<double>& RejectionCalibration::NullBound(int frames) const {
  return null_bound_[static_cast<std::size_t>(std::clamp(frames, 1, kCalibratedWindowLengths) - 1)];
}

double RejectionCalibration::NullThreshold(int frames, double false_accept_rate) const {
  const std::vector<double>& null = Null(frames);
  const std::vector<double>& bound = NullBound(frames);
  const auto accepted =
      std::upper_bound(bound.begin(), bound.end(), false_accept_rate) - bound.begin();
  return accepted == 0 ? null.front() - 1e-12 : null[static_cast<std::size_t>(accepted - 1)];
}

double RejectionCalibration::Threshold(int frames, double false_accept_rate,
                                       double known_accept_rate) const {
  const double null_threshold = NullThreshold(frames, false_accept_rate);
  if (known_.empty() || known_accept_rate <= 0) return null_threshold;
  return std::max(null_threshold, std::min(KnownQuantile(frames, known_accept_rate),
                                           NullThreshold(frames, kMostFalseAcceptRate)));
}

double RejectionCalibration::KnownQuantile(int frames, double share) const {
  const std::vector<double>& known = Known(frames);
  return known[std::min(known.size() - 1,
                        static_cast<std::size_t>(share * static_cast<double>(known.size())))];
}

double RejectionCalibration::KnownCeiling(int frames) const {
  if (known_.empty()) return std::numeric_limits<double>::infinity();
  return kKnownCeilingMargin * KnownQuantile(frames, kKnownWindowsAccepted);
}

double RejectionCalibration::KnownAcceptRate(double statistic, int frames) const {
  if (known_.empty()) return 1;
  const std::vector<double>& known = Known(frames);
  return static_cast<double>(std::upper_bound(known.begin(), known.end(), statistic) -
                             known.begin()) /
         static_cast<double>(known.size());
}

double RejectionCalibration::NullShare(double statistic, int frames) const {
  const std::vector<double>& null = Null(frames);
  return static_cast<double>(std::upper_bound(null.begin(), null.end(), statistic) - null.begin()) /
         static_cast<double>(null.size());
}

double RejectionCalibration::FalseAcceptRate(double statistic, int frames) const {
  const std::vector<double>& null = Null(frames);
  const auto at_or_below = std::upper_bound(null.begin(), null.end(), statistic) - null.begin();
  const double least = 1 / (static_cast<double>(null.size()) + 1);
  return at_or_below == 0
             ? least
             : std::max(least, NullBound(frames)[static_cast<std::size_t>(at_or_below - 1)]);
}

}  // namespace orbit
