#include "core/decision/active_vision.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/base/angles.h"

namespace orbit {
namespace {

void Validate(std::span<const MoveCandidate> candidates, int averaged_views) {
  if (averaged_views < 2) throw std::invalid_argument("averaged_views must be at least 2");
  for (const MoveCandidate& candidate : candidates) {
    if (candidate.object == nullptr) throw std::invalid_argument("move candidate without object");
  }
}

const MeanDescriptor& AveragedViewAt(const IndexedObject& object, int averaged_views,
                                     double azimuth) {
  const SectorViews& sectors = object.Sectors(averaged_views);
  const double width = 360.0 / averaged_views;
  const int sector =
      std::min(averaged_views - 1, static_cast<int>(std::floor(NormaliseAzimuth(azimuth) / width)));
  return sectors.descriptor[sector];
}

}  // namespace

Separation SideSeparation(std::span<const MoveCandidate> candidates, int averaged_views,
                          double offset) {
  Validate(candidates, averaged_views);
  std::vector<const MeanDescriptor*> views;
  for (const MoveCandidate& candidate : candidates) {
    views.push_back(&AveragedViewAt(*candidate.object, averaged_views, candidate.azimuth + offset));
  }
  Separation separation{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t a = 0; a < views.size(); ++a) {
    for (std::size_t b = a + 1; b < views.size(); ++b) {
      const double distance = 1.0 - Tanimoto(*views[a], *views[b]);
      separation.smallest = std::min(separation.smallest, distance);
      separation.sum += distance;
    }
  }
  if (views.size() < 2) separation.smallest = 0;
  return separation;
}

SuggestedMove SuggestMove(std::span<const MoveCandidate> candidates, int averaged_views,
                          std::span<const double> seen_turns) {
  Validate(candidates, averaged_views);
  if (candidates.size() < 2) return SuggestedMove::kNone;
  const double step = 360.0 / averaged_views;
  // A side is seen when an earlier frame lies on it, less than one and a half sectors away.
  const auto seen = [&](double sign) {
    for (double turn : seen_turns) {
      const double along = sign * AzimuthChange(0, turn);
      if (along > 0 && along < 1.5 * step) return true;
    }
    return false;
  };
  const bool right_seen = seen(+1);
  if (right_seen != seen(-1)) return right_seen ? SuggestedMove::kLeft : SuggestedMove::kRight;
  const Separation right = SideSeparation(candidates, averaged_views, +step);
  const Separation left = SideSeparation(candidates, averaged_views, -step);
  if (right.smallest != left.smallest) {
    return right.smallest > left.smallest ? SuggestedMove::kRight : SuggestedMove::kLeft;
  }
  if (right.sum != left.sum)
    return right.sum > left.sum ? SuggestedMove::kRight : SuggestedMove::kLeft;
  return SuggestedMove::kNone;
}

std::string_view MoveName(SuggestedMove move) {
  switch (move) {
    case SuggestedMove::kLeft: return "LEFT";
    case SuggestedMove::kRight: return "RIGHT";
    case SuggestedMove::kNone: break;
  }
  return "NONE";
}

}  // namespace orbit
