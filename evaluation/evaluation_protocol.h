// The evaluation protocol (docs/design.md#evaluation-protocol, the thesis' protocol made exact):
// what one trial asks of an engine and how its answer is scored. Pure: no images are read and
// no engine is run here (evaluation/evaluation_runner.h does both).
//
// One trial of object c with n query views:
//   1. n distinct views of c drawn uniformly at random (SampleTrial);
//   2. every view of c within kQueryExclusionDegrees of a query view, the query views
//      themselves included, is removed from c's model for this trial;
//   3. the query is ordered by increasing true azimuth (the camera sweeping round the object),
//      and each frame's device azimuth is its true azimuth + N(0, kQueryAzimuthNoiseDegrees) +
//      one offset, uniform in [0, 360), shared by the trial's frames;
//   4. the query images are the chosen views, unchanged (DF), motion-blurred (MB) or with
//      Gaussian noise (GN), core/descriptor/distortion.h (evaluation/distortion_spec.h names these
//      and other distortions for `orbit eval`);
//   5. a hit is a top-1 answer naming c (IsTopOneHit).
// Every random draw comes from TrialSeed(seed, object, n, trial), so a trial is the same for
// every method, distortion, descriptor variant, index mode and thread count.
//
// All functions are pure and thread-safe.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/engines/recognition_engine.h"
#include "core/model/object_model.h"

namespace orbit {

inline constexpr double kQueryExclusionDegrees = 10;    // inclusive: |difference| <= 10
inline constexpr double kQueryAzimuthNoiseDegrees = 3;  // standard deviation

// The seed of one trial: object is the object's position in the dataset, n the query length,
// trial the trial's number (0-based).
std::uint64_t TrialSeed(std::uint64_t seed, int object, int n, int trial);

// One trial's query, for an object whose views have the given azimuths.
struct TrialQuery {
  // Indices into the object's views, ordered by increasing true azimuth (ties: lower index).
  std::vector<int> views;
  // The device azimuth of each query frame (same order), degrees in [0, 360).
  std::vector<double> azimuths;
  // Indices of the object's views to remove from its model, ascending: every view whose
  // azimuth is within kQueryExclusionDegrees (circularly) of a query view's.
  std::vector<int> removed_views;
};

// Draws a trial: n distinct views, their device azimuths and the views to remove (see above).
// Throws std::invalid_argument when n < 1, when n exceeds the number of views, or when an
// azimuth is not finite.
TrialQuery SampleTrial(std::span<const double> view_azimuths, int n, std::uint64_t trial_seed);

// Every view whose azimuth is within kQueryExclusionDegrees (circularly) of one of
// `query_views`' (indices into `view_azimuths`; repeats allowed), ascending: step 2 above.
std::vector<int> ExcludedViews(std::span<const double> view_azimuths,
                               std::span<const int> query_views);

// Active vision (`orbit eval --active`): after its first views, the device takes each
// next view `step` degrees from its latest one in the direction the latest update suggested
// (kRight: increasing azimuth, kLeft: decreasing), and on in the direction it last went when
// the update said kNone. `direction` (+1 or -1) is that last direction; a move updates it.
// Returns the index of the view nearest that azimuth. REQUIRES: `latest` indexes
// `view_azimuths`.
int NextActiveView(std::span<const double> view_azimuths, int latest, SuggestedMove move,
                   double step, int& direction);

// `model` without the views listed in `removed_views` (ascending indices, as SampleTrial gives).
// Throws std::invalid_argument when an index is out of range or the list is not ascending.
ObjectModel WithoutViews(const ObjectModel& model, std::span<const int> removed_views);

// True when the ranking's first object is `expected`; false for an empty ranking.
bool IsTopOneHit(std::span<const RankedObject> ranking, ObjectId expected);

}  // namespace orbit
