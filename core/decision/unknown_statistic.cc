#include "core/decision/unknown_statistic.h"

#include <stdexcept>

namespace orbit {

double UnknownStatisticOf(double d1_sum, double d2_sum, double typical_sum) {
  // A runner-up as close as the winner (d2 = d1) gives 1; d2 = 0 with d1 = 0 is a frame equal
  // to views of both objects: as ambiguous as it gets, also 1.
  const double ratio = d2_sum > 0 ? d1_sum / d2_sum : (d1_sum > 0 ? 1e9 : 1.0);
  const double typical = typical_sum > 0 ? d1_sum / typical_sum : 0.0;
  return ratio + kTypicalTermWeight * typical;
}

double UnknownStatistic(const ObjectRows& winner, const ObjectRows* runner_up) {
  const std::vector<ModelView>& views = winner.object->model().views;
  double d1_sum = 0, d2_sum = 0, typical_sum = 0;
  for (std::size_t k = 0; k < winner.nearest.size(); ++k) {
    const NearestView& best = winner.nearest[k];
    d1_sum += 1 - best.closest();
    typical_sum += views[static_cast<std::size_t>(best.view)].typical_distance;
    if (runner_up != nullptr) {
      d2_sum += 1 - runner_up->nearest[k].closest();
    } else {
      d2_sum += 1.0;
    }
  }
  return UnknownStatisticOf(d1_sum, d2_sum, typical_sum);
}

double UnknownStatistic(std::span<const QueryFrame> window, const IndexedObject& winner,
                        const IndexedObject* runner_up) {
  if (window.empty()) throw std::invalid_argument("UnknownStatistic needs at least one frame");
  if (winner.model().views.empty()) throw std::invalid_argument("the winner has no views");
  SimilarityRows rows;
  for (std::size_t k = 0; k < window.size(); ++k) rows.PushFrame();
  const ObjectRows winner_rows = rows.For(window, winner);
  if (runner_up == nullptr) return UnknownStatistic(winner_rows, nullptr);
  const ObjectRows runner_up_rows = rows.For(window, *runner_up);
  return UnknownStatistic(winner_rows, &runner_up_rows);
}

}  // namespace orbit
