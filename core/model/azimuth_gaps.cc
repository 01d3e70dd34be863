#include "core/model/azimuth_gaps.h"

#include <algorithm>

#include "core/base/angles.h"

namespace orbit {

std::vector<AzimuthGap> AzimuthGaps(std::vector<double> azimuths, double wider_than) {
  for (double& azimuth : azimuths) azimuth = NormaliseAzimuth(azimuth);
  std::sort(azimuths.begin(), azimuths.end());
  // Views at one azimuth leave no arc between them.
  azimuths.erase(std::unique(azimuths.begin(), azimuths.end()), azimuths.end());
  std::vector<AzimuthGap> gaps;
  for (std::size_t k = 0; k < azimuths.size(); ++k) {
    const AzimuthGap gap{azimuths[k], azimuths[(k + 1) % azimuths.size()]};
    // One azimuth alone leaves the whole circle open.
    if (azimuths.size() == 1 || gap.width() > wider_than) gaps.push_back(gap);
  }
  return gaps;
}

double AzimuthGap::width() const {
  const double width = NormaliseAzimuth(to - from);
  return width == 0 ? 360 : width;
}

}  // namespace orbit
