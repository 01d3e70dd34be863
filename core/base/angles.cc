#include "core/base/angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace orbit {

double WrapDegrees(double degrees) {
  double wrapped = std::fmod(degrees, 360.0);  // (-360, 360), exact
  if (wrapped <= -180.0) wrapped += 360.0;
  if (wrapped > 180.0) wrapped -= 360.0;
  return wrapped;
}

double NormaliseAzimuth(double degrees) {
  double normalised = std::fmod(degrees, 360.0);
  if (normalised < 0) normalised += 360.0;
  // -1e-20 + 360 rounds to 360: keep the result inside [0, 360); -0.0 becomes +0.0.
  return normalised >= 360.0 || normalised == 0 ? 0.0 : normalised;
}

double AzimuthChange(double from, double to) {
  const double change = to - from;
  // Far-apart finite azimuths (1e308 and -1e308) overflow the difference; the turn between them
  // is the turn between their equivalents in [0, 360).
  if (!std::isfinite(change)) return WrapDegrees(NormaliseAzimuth(to) - NormaliseAzimuth(from));
  return WrapDegrees(change);
}

double DegreesToRadians(double degrees) { return degrees * (std::numbers::pi / 180.0); }

double ArcOverlap(const Arc& a, const Arc& b) {
  for (const Arc* arc : {&a, &b}) {
    if (!std::isfinite(arc->start) || !std::isfinite(arc->width) || arc->width < 0 ||
        arc->width > 360) {
      throw std::invalid_argument("ArcOverlap: arc width must be finite and in [0, 360]");
    }
  }
  // On the line, `a` is [a0, a0 + wa) with a0 in [0, 360), inside [0, 720). The copies of `b`
  // shifted by -360, 0 and +360 cover [0, 720) and are disjoint (wb <= 360), and `a` covers
  // each point of the circle at most once, so the overlaps with the copies add up exactly.
  const double a0 = NormaliseAzimuth(a.start);
  const double a1 = a0 + a.width;
  const double b0 = NormaliseAzimuth(b.start);
  double overlap = 0;
  for (const double shift : {-360.0, 0.0, 360.0}) {
    const double lo = std::max(a0, b0 + shift);
    const double hi = std::min(a1, b0 + shift + b.width);
    if (hi > lo) overlap += hi - lo;
  }
  return std::min(overlap, std::min(a.width, b.width));
}

}  // namespace orbit
