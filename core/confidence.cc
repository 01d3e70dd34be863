#include "core/confidence.h"

#include <cmath>

namespace orbit {

double Confidence(double unknown_statistic) {
  if (!std::isfinite(unknown_statistic)) return 0;
  return 1 / (1 + std::exp(-(kConfidenceIntercept - kConfidenceSlope * unknown_statistic)));
}

}  // namespace orbit
