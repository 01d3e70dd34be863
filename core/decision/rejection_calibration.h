// RejectionCalibration: the threshold of the calibrated accept / unknown rule, chosen from a
// target false-accept rate and computed from the model set alone, with no labelled unknown
// objects (docs/design.md#calibrated-rule).
//
// Leave one object out: each known object in turn plays an object the server has never seen.
// Some of its views are queried against every other object; a window of n of them is answered
// as a session would answer it (the winner and the runner-up are the two objects with the
// largest summed best-view similarity over the window's frames, a blend of two neighbouring
// views counting as a view, docs/design.md#blended-views) and gives one value of the
// unknown statistic U (core/decision/unknown_statistic.h). Those values are the null distribution:
// what U looks like when the object in front of the camera is unknown. A window whose U is at or
// below the threshold for a target false-accept rate f is accepted, and an unknown object's
// window is then accepted with probability at most about f, provided unknown objects differ from
// the known ones the way known ones differ among themselves. Look-alikes of enrolled objects are
// in the null too (an object whose twin is enrolled), so on a model set with few of them the
// measured rate is below f.
//
// The bound: the null's share at a threshold is the mean over its left-out objects of each
// one's share, and with few objects that mean is a rough estimate (an object nobody enrolled may
// look like none of them, or like one of them as closely as a twin). The threshold for f is
// therefore the largest null value at which an upper confidence bound of that mean stays at or
// below f: the mean plus kNullShareBoundSigmas standard errors over objects. With many objects
// the bound lies close to the share (the threshold near the null's f-quantile); with few it lies
// well above it, and the rule is stricter (docs/design.md#calibrated-rule).
//
// The known share: where look-alikes are enrolled, a left-out object's windows look as known as
// an enrolled object's own, and the null's threshold for a low target rejects most of the known
// objects' windows too. The calibration sees this in its own known windows (below), so the
// threshold is raised until a given share of them is accepted, within a most that keeps the
// null's false-accept rate bounded (docs/design.md#known-share).
//
// The known ceiling: with few objects the null is a handful of object pairs (two objects: one
// pair) and says little about an object nobody enrolled, and an unknown window meets one object
// more than a left-out object met; the measured rate then lies far above f. So the threshold
// never exceeds what the known objects' own windows need: each sampled view, matched against
// its own object's views outside kOwnNeighbourhoodDegrees of it and the blends of its pairs
// of views outside it (a query falls between enrolled views), gives a known window the same way,
// and the rule accepts a window only at or below both the null's f-quantile and the known ceiling,
// a margin above the known windows' kKnownWindowsAccepted quantile. With many objects the null's
// quantile usually lies below the ceiling and rules alone (docs/design.md#known-ceiling).
//
// Sampling keeps the cost bounded: at most `max_sampled_views` views (spread evenly in azimuth
// over every object, or one view of each of `max_sampled_views` objects spread evenly over a
// larger index); windows draw their frames from the sampled views of one object, with
// replacement. Up to kScanEveryObjectUpTo objects a sampled view is compared with every view of
// the index; above, with the views of the objects ObjectCandidates proposes for
// its object's sampled views, each scored exactly, and an object no view proposes is taken to
// answer a window less well than those that are (docs/design.md#calibrated-rule).
//
// Immutable after construction; thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/index/view_index.h"

namespace orbit {

// Window lengths with a null distribution of their own; longer windows use the longest one's
// threshold (U's null narrows as n grows, so this rejects a little more than needed).
inline constexpr int kCalibratedWindowLengths = 16;

// A known object's window matches its own views no nearer than this in azimuth to each
// frame's: a query falls between enrolled views, not on one.
inline constexpr double kOwnNeighbourhoodDegrees = 10;
// The known windows' quantile the ceiling starts from, and the factor it is raised by: a known
// object seen against another background or in another light than at enrollment lies further
// from its views than they lie from each other (docs/design.md#known-ceiling).
// The one-sided normal bound at 90% confidence on the null's share.
inline constexpr double kNullShareBoundSigmas = 1.2816;

inline constexpr double kKnownWindowsAccepted = 0.99;
inline constexpr double kKnownCeilingMargin = 1.5;

// The most the threshold is raised to for the known objects' windows: the null's threshold at
// this false-accept rate (docs/design.md#known-share).
inline constexpr double kMostFalseAcceptRate = 0.4;

// In an index of more than kScanEveryObjectUpTo objects, the objects proposed for each sampled
// view that its object's views are scored against.
inline constexpr int kLeftOutCandidatesPerView = 32;

struct CalibrationOptions {
  int max_sampled_views = 2048;   // views compared with the index (>= 1)
  int windows_per_length = 2000;  // null values drawn per window length (>= 1)
  std::uint64_t seed = 1;         // the window draws
  int threads = 1;                // the sampled views are compared on this many (>= 1)
  // Above this many objects, candidates only (the exact reference they are measured by: any
  // number at or above the index's objects).
  std::size_t scan_every_object_up_to = kScanEveryObjectUpTo;
};

class RejectionCalibration {
 public:
  // An empty calibration: calibrated() is false.
  RejectionCalibration() = default;

  // The null distributions of `index`. Empty (not calibrated) when the index holds fewer than
  // two objects: no object can then play an unknown one. Throws std::invalid_argument for
  // options out of range.
  static RejectionCalibration FromIndex(const ViewIndexSnapshot& index,
                                        const CalibrationOptions& options = {});

  bool calibrated() const { return !null_.empty(); }
  // Whether some object had a view outside its own neighbourhood to draw known windows from.
  bool has_known_windows() const { return !known_.empty(); }

  // The largest U the null accepts for a window of `frames` frames at the target false-accept
  // rate (in (0, 1)): the largest null value whose FalseAcceptRate is at most the target; just
  // below the least value when none is. REQUIRES: calibrated(), frames >= 1.
  double NullThreshold(int frames, double false_accept_rate) const;

  // The threshold of the calibrated rule: the null's threshold for `false_accept_rate`, raised
  // to the U below which `known_accept_rate` of the known objects' simulated windows fall when
  // they need more, but never above the null's threshold for kMostFalseAcceptRate (nor below the
  // first). known_accept_rate 0, or no known windows: the null's threshold alone
  // (docs/design.md#known-share). REQUIRES: calibrated(), frames >= 1, false_accept_rate in
  // (0, 1), known_accept_rate in [0, 1).
  double Threshold(int frames, double false_accept_rate, double known_accept_rate) const;

  // The known ceiling: kKnownCeilingMargin times the U below which kKnownWindowsAccepted of the
  // known objects' simulated windows of `frames` frames fall; infinity when no object has a view
  // outside its own neighbourhood. REQUIRES: calibrated(), frames >= 1.
  double KnownCeiling(int frames) const;

  // The share of the known objects' simulated windows at or below `statistic`, in [0, 1] (1
  // without any). REQUIRES: calibrated(), frames >= 1.
  double KnownAcceptRate(double statistic, int frames) const;

  // The share of the null at or below `statistic` for a window of `frames` frames, in [0, 1]:
  // how often a left-out object's window looked at least this known. REQUIRES: calibrated(),
  // frames >= 1.
  double NullShare(double statistic, int frames) const;

  // The rule's p-value, in (0, 1]: the upper bound of NullShare at `statistic` over the null's
  // objects, never below one window's worth (1 / (N + 1)). A window is accepted by the null at
  // target f iff its FalseAcceptRate is at most f. REQUIRES: calibrated(), frames >= 1.
  double FalseAcceptRate(double statistic, int frames) const;

  // The sorted U of the null's windows and of the known objects' windows (empty without any) of
  // `frames` frames. REQUIRES: calibrated(), frames >= 1.
  std::span<const double> NullWindows(int frames) const { return Null(frames); }
  std::span<const double> KnownWindows(int frames) const {
    return known_.empty() ? std::span<const double>() : std::span<const double>(Known(frames));
  }

  // The objects and views the null was drawn from.
  int sampled_objects() const { return sampled_objects_; }
  int sampled_views() const { return sampled_views_; }

 private:
  const std::vector<double>& Null(int frames) const;
  const std::vector<double>& NullBound(int frames) const;
  const std::vector<double>& Known(int frames) const;  // REQUIRES: !known_.empty()
  // The value at position floor(share * N) of the N sorted known windows of `frames` frames (the
  // last for share 1). REQUIRES: !known_.empty(), share in [0, 1].
  double KnownQuantile(int frames, double share) const;

  std::vector<std::vector<double>> null_;  // [n - 1]: sorted U values for windows of n frames
  // [n - 1][i]: the bound on the share of the null at or below null_[n - 1][i], non-decreasing
  // in i, equal within tied values.
  std::vector<std::vector<double>> null_bound_;
  std::vector<std::vector<double>> known_;  // [n - 1]: the same for known objects' windows
  int sampled_objects_ = 0;
  int sampled_views_ = 0;
};

}  // namespace orbit
