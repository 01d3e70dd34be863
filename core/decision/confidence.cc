#include "core/decision/confidence.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace orbit {

double Confidence(double unknown_statistic, int frames) {
  if (!std::isfinite(unknown_statistic)) return 0;
  const double log_frames = std::log(static_cast<double>(frames));
  const double z = kConfidenceIntercept + kConfidenceStatistic * unknown_statistic +
                   kConfidenceFrames * log_frames +
                   kConfidenceInteraction * unknown_statistic * log_frames;
  return 1 / (1 + std::exp(-z));
}

namespace {

// One set's windows taken nearest first from a statistic: a cursor on each side of its place.
class Nearest {
 public:
  Nearest(std::span<const double> sorted, double statistic)
      : sorted_(sorted),
        statistic_(statistic),
        above_(std::lower_bound(sorted.begin(), sorted.end(), statistic) - sorted.begin()),
        below_(above_ - 1),
        weight_(sorted.empty() ? 0 : 1.0 / static_cast<double>(sorted.size())) {}

  // The distance to the nearest window not yet taken; infinity when every one is.
  double Distance() const {
    return std::min(below_ >= 0 ? statistic_ - sorted_[below_] : kNone,
                    above_ < std::ssize(sorted_) ? sorted_[above_] - statistic_ : kNone);
  }
  // Takes that window; returns its share of the set.
  double Take() {
    const bool from_below =
        below_ >= 0 && (above_ >= std::ssize(sorted_) ||
                        statistic_ - sorted_[below_] <= sorted_[above_] - statistic_);
    from_below ? --below_ : ++above_;
    return weight_;
  }

 private:
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  std::span<const double> sorted_;
  double statistic_;
  std::ptrdiff_t above_, below_;
  double weight_;
};

}  // namespace

double CatalogueConfidence(const RejectionCalibration& calibration, double judged_as_known,
                           double judged, int frames) {
  if (!std::isfinite(judged_as_known) || !std::isfinite(judged)) return 0;
  Nearest known(calibration.KnownWindows(frames), judged_as_known);
  Nearest left_out(calibration.NullWindows(frames), judged);
  // The nearest windows of both sets, one at a time (a tie to the known one), until they hold
  // kConfidenceNeighbourhood as shares of their sets.
  double known_share = 0, left_out_share = 0;
  while (known_share + left_out_share < kConfidenceNeighbourhood) {
    const double to_known = known.Distance(), to_left_out = left_out.Distance();
    if (std::isinf(to_known) && std::isinf(to_left_out)) break;
    if (to_known <= to_left_out) {
      known_share += known.Take();
    } else {
      left_out_share += left_out.Take();
    }
  }
  const double right = kRightPrior * known_share;
  return right / (right + (1 - kRightPrior) * left_out_share);
}

}  // namespace orbit
