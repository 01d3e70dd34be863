#include "core/index/indexed_object.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/base/angles.h"

namespace orbit {
namespace {

template <typename Q, typename C>
double GeneralisedTanimoto(const Q& q, const C& c) {
  double qc = 0, qq = 0, cc = 0;
  for (int i = 0; i < kDescriptorSize; ++i) {
    const double qi = q[i], ci = c[i];
    qc += qi * ci;
    qq += qi * qi;
    cc += ci * ci;
  }
  if (qq == 0 && cc == 0) return 1.0;
  const double denominator = qq + cc - qc;
  return denominator > 0 ? qc / denominator : 0.0;
}

// Circular distance between two azimuths, in [0, 180].
double CircularDistance(double a, double b) { return std::abs(AzimuthChange(b, a)); }

ViewSum SumOf(const ObjectModel& model, const std::vector<int>& views) {
  ViewSum sum{};
  for (const int v : views) {
    for (int i = 0; i < kDescriptorSize; ++i) sum[i] += model.views[v].descriptor[i];
  }
  return sum;
}

MeanDescriptor MeanOf(const ViewSum& sum, std::size_t count) {
  MeanDescriptor mean{};
  for (int i = 0; i < kDescriptorSize; ++i) {
    mean[i] = static_cast<float>(sum[i] / static_cast<double>(count));
  }
  return mean;
}

}  // namespace

double Tanimoto(const DescriptorValues& q, const MeanDescriptor& c) {
  return GeneralisedTanimoto(q, c);
}

double Tanimoto(const MeanDescriptor& q, const MeanDescriptor& c) {
  return GeneralisedTanimoto(q, c);
}

SectorViews ComputeSectorViews(const ObjectModel& model, int count) {
  if (count < 1) throw std::invalid_argument("sector count must be at least 1");
  if (model.views.empty()) throw std::invalid_argument("object has no views");
  const double width = 360.0 / count;
  SectorViews sectors;
  sectors.count = count;
  sectors.views.resize(count);
  for (int v = 0; v < static_cast<int>(model.views.size()); ++v) {
    const double azimuth = NormaliseAzimuth(model.views[v].azimuth);
    const int s = std::min(count - 1, static_cast<int>(std::floor(azimuth / width)));
    sectors.views[s].push_back(v);
  }
  for (int s = 0; s < count; ++s) {
    std::vector<int> members = sectors.views[s];
    if (members.empty()) {
      // Stand-in for an empty sector: the views nearest its centre.
      const double centre = (s + 0.5) * width;
      double nearest = 360;
      for (const ModelView& view : model.views) {
        nearest = std::min(nearest, CircularDistance(view.azimuth, centre));
      }
      for (int v = 0; v < static_cast<int>(model.views.size()); ++v) {
        if (CircularDistance(model.views[v].azimuth, centre) <= nearest + 1e-9)
          members.push_back(v);
      }
    }
    sectors.views[s] = members;
    sectors.sum.push_back(SumOf(model, members));
    sectors.descriptor.push_back(MeanOf(sectors.sum.back(), members.size()));
    const MeanDescriptor& d = sectors.descriptor.back();
    double norm = 0;
    for (const float x : d) norm += static_cast<double>(x) * x;
    sectors.squared_norm.push_back(norm);
  }
  return sectors;
}

IndexedObject::IndexedObject(ObjectModel model) : model_(std::move(model)) {
  if (model_.views.empty()) {
    throw std::invalid_argument("object " + std::to_string(model_.id) + " has no views");
  }
  for (ModelView& view : model_.views) {
    if (!std::isfinite(view.azimuth)) {
      throw std::invalid_argument("object " + std::to_string(model_.id) +
                                  ": a view's azimuth is not finite");
    }
    ValidateDescriptorValues(view.descriptor,
                             "object " + std::to_string(model_.id) + " descriptor");
    view.azimuth = NormaliseAzimuth(view.azimuth);
    std::int32_t norm = 0;
    for (const std::uint8_t value : view.descriptor) norm += value * value;
    squared_norms_.push_back(norm);
  }
  std::vector<DescriptorValues> descriptors;
  for (const ModelView& view : model_.views) descriptors.push_back(view.descriptor);
  view_bins_ = ViewBins(descriptors);
  by_azimuth_.resize(model_.views.size());
  std::iota(by_azimuth_.begin(), by_azimuth_.end(), 0);
  std::stable_sort(by_azimuth_.begin(), by_azimuth_.end(), [this](int a, int b) {
    return model_.views[a].azimuth < model_.views[b].azimuth;
  });
  for (const int v : by_azimuth_) sorted_azimuths_.push_back(model_.views[v].azimuth);
  const std::size_t count = by_azimuth_.size();
  for (std::size_t i = 0; i < count && count > 1; ++i) {
    const int a = by_azimuth_[i];
    const int b = by_azimuth_[(i + 1) % count];
    const ModelView& first = model_.views[a];
    const ModelView& second = model_.views[b];
    // Two views at one azimuth are 0 apart, not a full turn: they blend into neither.
    const double apart = NormaliseAzimuth(second.azimuth - first.azimuth);
    if (apart == 0 || apart > kBlendViewsUpTo || first.elevation != second.elevation) continue;
    std::int32_t sum_norm = 0;
    for (std::size_t d = 0; d < kDescriptorSize; ++d) {
      const int sum = first.descriptor[d] + second.descriptor[d];
      sum_norm += sum * sum;
    }
    neighbour_pairs_.push_back({a, b, sum_norm});
  }
}

std::pair<int, int> IndexedObject::NeighbourViews(double azimuth) const {
  const double target = NormaliseAzimuth(azimuth);
  const int n = static_cast<int>(by_azimuth_.size());
  // First view at or after the target, circularly.
  const auto it = std::lower_bound(
      by_azimuth_.begin(), by_azimuth_.end(), target,
      [this](int view, double value) { return model_.views[view].azimuth < value; });
  const int after = static_cast<int>(it - by_azimuth_.begin()) % n;
  if (model_.views[by_azimuth_[after]].azimuth == target) {
    return {by_azimuth_[after], by_azimuth_[after]};
  }
  const int before = (after + n - 1) % n;
  return {by_azimuth_[before], by_azimuth_[after]};
}

int IndexedObject::NearestView(double azimuth) const {
  const auto [before, after] = NeighbourViews(azimuth);
  const double d_before = CircularDistance(model_.views[before].azimuth, azimuth);
  const double d_after = CircularDistance(model_.views[after].azimuth, azimuth);
  return d_after < d_before ? after : before;
}

const SectorViews& IndexedObject::Sectors(int count) const {
  const SectorViews* latest = latest_sectors_.load(std::memory_order_acquire);
  if (latest != nullptr && latest->count == count) return *latest;
  if (count < 1) throw std::invalid_argument("sector count must be at least 1");
  MutexLock lock(&sectors_mutex_);
  std::unique_ptr<const SectorViews>& entry = sectors_[count];
  if (!entry) entry = std::make_unique<const SectorViews>(ComputeSectorViews(model_, count));
  latest_sectors_.store(entry.get(), std::memory_order_release);
  return *entry;
}

}  // namespace orbit
