// IndexedObject: one known object as the index holds it, with what the engines precompute from
// its model: its views ordered by azimuth (to find the view at a given orientation) and its
// sector views (the mean CEDD of the views in each of N equal azimuth sectors: the HMM's state
// descriptors and active vision's averaged views, docs/design.md#sector-views).
//
// Thread safety: immutable after construction except for the sector-view cache, which is
// filled under an internal mutex; every method is const and safe to call from many threads.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "core/base/mutex.h"
#include "core/descriptor/descriptor.h"
#include "core/index/view_bins.h"
#include "core/model/object_model.h"

namespace orbit {

// A real-valued descriptor: the mean of several CEDD descriptors.
using MeanDescriptor = std::array<float, kDescriptorSize>;
// The exact sum of several CEDD descriptors, bin by bin.
using ViewSum = std::array<std::int32_t, kDescriptorSize>;

// TC generalised to real values, q.c / (q.q + c.c - q.c), with the same conventions as
// Tanimoto() for zero vectors. Equal to Tanimoto() on integer-valued inputs.
double Tanimoto(const DescriptorValues& q, const MeanDescriptor& c);
double Tanimoto(const MeanDescriptor& q, const MeanDescriptor& c);

// The N equal azimuth sectors of an object: sector s covers model azimuths
// [s * 360/N, (s+1) * 360/N). descriptor[s] is the mean of the views whose azimuth falls in
// sector s; a sector with no view takes the mean of the views nearest (circularly) to its
// centre, so that every state has a descriptor even after the protocol removes views.
struct SectorViews {
  int count = 0;
  std::vector<MeanDescriptor> descriptor;  // [count]
  std::vector<ViewSum> sum;                // [count]: descriptor * (views in the mean)
  std::vector<double> squared_norm;        // [count]: descriptor . descriptor
  // [count]: the model views the mean was taken over (the sector's own, or the stand-ins)
  std::vector<std::vector<int>> views;
};

// Sector views of `model` for `count` sectors (the function the cache calls).
// Throws std::invalid_argument when count < 1 or the model has no views.
SectorViews ComputeSectorViews(const ObjectModel& model, int count);

// Two views next to each other in azimuth, whose blend (the mean of their descriptors) stands
// for the view halfway between them (docs/design.md#blended-views).
struct NeighbourPair {
  int first = 0;   // a view, as an index into ObjectModel::views
  int second = 0;  // the next view counter-clockwise (in increasing azimuth, across 360)
  // |c_first + c_second|^2: with the frame's products with each view, the TC of the blend
  // without touching its descriptor.
  std::int32_t sum_squared_norm = 0;
};

// The widest arc, in degrees, across which two neighbouring views are blended: farther apart
// than a quarter turn, they show different sides of the object, and their mean looks like
// neither (docs/design.md#blended-views).
inline constexpr double kBlendViewsUpTo = 90;

class IndexedObject {
 public:
  // Throws std::invalid_argument when the model has no views, a value exceeds 7 or an azimuth
  // is not finite. Azimuths are normalised to [0, 360).
  explicit IndexedObject(ObjectModel model);

  const ObjectModel& model() const { return model_; }
  ObjectId id() const { return model_.id; }
  int view_count() const { return static_cast<int>(model_.views.size()); }

  // Indices of model().views in increasing azimuth order (ties: lower index first).
  const std::vector<int>& views_by_azimuth() const { return by_azimuth_; }
  // Their azimuths, in that order ([0, 360), ascending): side by side, for the pose estimate's
  // sweep on every frame, instead of one model view (and cache line) each.
  const std::vector<double>& sorted_azimuths() const { return sorted_azimuths_; }

  // c.c of each view's descriptor, in model().views order: the half of a Tanimoto coefficient
  // that does not depend on the frame (core/index/similarity_rows.h).
  const std::vector<std::int32_t>& squared_norms() const { return squared_norms_; }

  // The views' descriptors bin by bin, 4 bits a value (core/index/view_bins.h): what a frame's row
  // of Tanimoto coefficients (core/index/similarity_rows.h) reads.
  const ViewBins& view_bins() const { return view_bins_; }

  // The pairs of views next to each other in azimuth, at the same elevation (or both without
  // one) and at most kBlendViewsUpTo degrees apart, in increasing azimuth of `first`.
  const std::vector<NeighbourPair>& neighbour_pairs() const { return neighbour_pairs_; }

  // The views on either side of `azimuth` (degrees, any value): `first` is the view at or
  // counter-clockwise-before it (largest azimuth <= it, circularly) and `second` the view at or
  // after it (smallest azimuth >= it, circularly). Both equal when a view sits exactly there
  // or the object has one view.
  std::pair<int, int> NeighbourViews(double azimuth) const;

  // The view whose azimuth is closest to `azimuth` circularly (ties: NeighbourViews().first).
  int NearestView(double azimuth) const;

  // Sector views for `count` sectors, computed on first use and cached.
  // Throws std::invalid_argument when count < 1.
  const SectorViews& Sectors(int count) const ABSL_LOCKS_EXCLUDED(sectors_mutex_);

 private:
  ObjectModel model_;
  std::vector<int> by_azimuth_;
  std::vector<double> sorted_azimuths_;
  std::vector<std::int32_t> squared_norms_;
  ViewBins view_bins_;
  std::vector<NeighbourPair> neighbour_pairs_;
  mutable Mutex sectors_mutex_;
  // An entry, once made, is never changed nor removed: Sectors() returns it unlocked.
  mutable std::map<int, std::unique_ptr<const SectorViews>> sectors_
      ABSL_GUARDED_BY(sectors_mutex_);
  // The entry Sectors() returned last, published after it was made: a session's every frame
  // asks for the same count, which is then read without the lock.
  mutable std::atomic<const SectorViews*> latest_sectors_{nullptr};
};

}  // namespace orbit
