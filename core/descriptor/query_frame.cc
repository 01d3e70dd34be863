#include "core/descriptor/query_frame.h"

#include "core/base/angles.h"

namespace orbit {

std::optional<double> MeasuredTurn(const QueryFrame& from, const QueryFrame& to) {
  if (!from.azimuth || !to.azimuth) return std::nullopt;
  return AzimuthChange(*from.azimuth, *to.azimuth);
}

}  // namespace orbit
