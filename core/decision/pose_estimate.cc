#include "core/decision/pose_estimate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/base/angles.h"

namespace orbit {

PoseEstimate EstimatePose(std::span<const QueryFrame> window, const IndexedObject& object) {
  if (window.empty()) throw std::invalid_argument("EstimatePose needs at least one frame");
  if (object.model().views.empty()) {
    throw std::invalid_argument("EstimatePose: the object has no views");
  }
  SimilarityRows rows;
  for (std::size_t k = 0; k < window.size(); ++k) rows.PushFrame();
  return EstimatePose(window, rows.For(window, object));
}

namespace {

double Circular(double a, double b) {  // a, b in [0, 360)
  const double d = std::abs(a - b);
  return std::min(d, 360 - d);
}

// For each view in azimuth order (positions into `azimuths`, ascending, in [0, 360)), the
// position of the view nearest to its azimuth + turn: what IndexedObject::NearestView gives,
// found in one sweep, since the targets advance round the circle with the views (ties: the
// view before).
std::vector<int> NearestAfterTurn(const std::vector<double>& azimuths, double turn) {
  const int m = static_cast<int>(azimuths.size());
  const double shift = NormaliseAzimuth(turn);
  auto target = [&](int i) {
    const double t = azimuths[i] + shift;
    return t >= 360 ? t - 360 : t;
  };
  int position = 0;
  for (int j = 1; j < m; ++j) {
    if (Circular(azimuths[j], target(0)) < Circular(azimuths[position], target(0))) position = j;
  }
  std::vector<int> nearest(m);
  for (int i = 0; i < m; ++i) {
    const double t = target(i);
    for (int step = 0; step < m; ++step) {
      const int next = (position + 1) % m;
      if (!(Circular(azimuths[next], t) < Circular(azimuths[position], t))) break;
      position = next;
    }
    nearest[i] = position;
  }
  return nearest;
}

}  // namespace

PoseEstimate EstimatePose(std::span<const QueryFrame> window, const ObjectRows& rows) {
  const IndexedObject& object = *rows.object;
  const std::vector<int>& order = object.views_by_azimuth();
  const std::vector<double>& azimuths = object.sorted_azimuths();
  const QueryFrame& latest = window.back();
  // score[i]: the mean TC when the view at position i of `order` faces the latest frame.
  std::vector<double> score(order.size(), 0);
  int counted = 0;
  for (std::size_t k = 0; k < window.size(); ++k) {
    std::optional<double> turn = 0.0;
    if (k + 1 < window.size()) turn = MeasuredTurn(latest, window[k]);
    if (!turn) continue;  // no measured turn to the latest frame: left out
    const std::vector<int> nearest = NearestAfterTurn(azimuths, *turn);
    const std::span<const float> row = rows.rows[k];
    for (std::size_t i = 0; i < order.size(); ++i) score[i] += row[order[nearest[i]]];
    ++counted;
  }
  std::size_t best = 0;  // ties: the smaller azimuth, the first in azimuth order
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (score[i] > score[best]) best = i;
  }
  PoseEstimate pose{azimuths[best], 0};
  const double tolerance = kPoseSimilarityTolerance * counted;  // scores are sums here
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (score[i] < score[best] - tolerance) continue;
    pose.spread = std::max(pose.spread, Circular(pose.azimuth, azimuths[i]));
  }
  return pose;
}

}  // namespace orbit
