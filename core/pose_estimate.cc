#include "core/pose_estimate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/angles.h"
#include "core/similarity.h"

namespace orbit {

PoseEstimate EstimatePose(std::span<const QueryFrame> window, const IndexedObject& object) {
  const std::vector<ModelView>& views = object.model().views;
  if (window.empty()) throw std::invalid_argument("EstimatePose needs at least one frame");
  if (views.empty()) throw std::invalid_argument("EstimatePose: the object has no views");
  const QueryFrame& latest = window.back();
  // The frames that count and where each lies relative to the latest one.
  std::vector<std::pair<const QueryFrame*, double>> frames;
  for (const QueryFrame& frame : window) {
    if (&frame == &latest) {
      frames.emplace_back(&frame, 0.0);
    } else if (const std::optional<double> turn = MeasuredTurn(latest, frame)) {
      frames.emplace_back(&frame, *turn);
    }
  }
  std::vector<double> score(views.size(), 0);
  for (std::size_t v = 0; v < views.size(); ++v) {
    for (const auto& [frame, turn] : frames) {
      const int view = object.NearestView(views[v].azimuth + turn);
      score[v] += Tanimoto(frame->descriptor.values, views[view].descriptor);
    }
    score[v] /= static_cast<double>(frames.size());
  }
  std::size_t best = 0;
  for (std::size_t v = 1; v < views.size(); ++v) {
    if (score[v] > score[best] ||
        (score[v] == score[best] && views[v].azimuth < views[best].azimuth)) {
      best = v;
    }
  }
  PoseEstimate pose{NormaliseAzimuth(views[best].azimuth), 0};
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (score[v] < score[best] - kPoseSimilarityTolerance) continue;
    pose.spread = std::max(pose.spread, std::abs(AzimuthChange(pose.azimuth, views[v].azimuth)));
  }
  return pose;
}

}  // namespace orbit
