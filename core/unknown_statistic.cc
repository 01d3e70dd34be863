#include "core/unknown_statistic.h"

#include <stdexcept>

#include "core/similarity.h"

namespace orbit {
namespace {

// The frame's best view of `object`: {TC, that view's Ttyp}.
std::pair<double, double> BestView(const DescriptorValues& frame, const IndexedObject& object) {
  double best = -1, typical = 0;
  for (const ModelView& view : object.model().views) {
    const double similarity = Tanimoto(frame, view.descriptor);
    if (similarity > best) {
      best = similarity;
      typical = view.typical_distance;
    }
  }
  return {best, typical};
}

}  // namespace

double UnknownStatisticOf(double d1_sum, double d2_sum, double typical_sum) {
  // A runner-up as close as the winner (d2 = d1) gives 1; d2 = 0 with d1 = 0 is a frame equal
  // to views of both objects: as ambiguous as it gets, also 1.
  const double ratio = d2_sum > 0 ? d1_sum / d2_sum : (d1_sum > 0 ? 1e9 : 1.0);
  const double typical = typical_sum > 0 ? d1_sum / typical_sum : 0.0;
  return ratio + kTypicalTermWeight * typical;
}

double UnknownStatistic(std::span<const QueryFrame> window, const IndexedObject& winner,
                        const IndexedObject* runner_up) {
  if (window.empty()) throw std::invalid_argument("UnknownStatistic needs at least one frame");
  if (winner.model().views.empty()) throw std::invalid_argument("the winner has no views");
  double d1_sum = 0, d2_sum = 0, typical_sum = 0;
  for (const QueryFrame& frame : window) {
    const auto [winner_similarity, typical] = BestView(frame.descriptor.values, winner);
    d1_sum += 1 - winner_similarity;
    typical_sum += typical;
    d2_sum += runner_up != nullptr && !runner_up->model().views.empty()
                  ? 1 - BestView(frame.descriptor.values, *runner_up).first
                  : 1.0;
  }
  return UnknownStatisticOf(d1_sum, d2_sum, typical_sum);
}

}  // namespace orbit
