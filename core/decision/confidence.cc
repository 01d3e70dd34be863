#include "core/decision/confidence.h"

#include <cmath>

namespace orbit {

double Confidence(double unknown_statistic, int frames) {
  if (!std::isfinite(unknown_statistic)) return 0;
  const double log_frames = std::log(static_cast<double>(frames));
  const double z = kConfidenceIntercept + kConfidenceStatistic * unknown_statistic +
                   kConfidenceFrames * log_frames +
                   kConfidenceInteraction * unknown_statistic * log_frames;
  return 1 / (1 + std::exp(-z));
}

}  // namespace orbit
