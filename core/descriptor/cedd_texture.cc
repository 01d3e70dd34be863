#include "core/descriptor/cedd_texture.h"

#include <algorithm>
#include <cmath>

namespace orbit::cedd {
namespace {

constexpr double kT0 = 14;    // below this largest magnitude the block is non-edge
constexpr double kT1 = 0.68;  // non-directional
constexpr double kT2 = 0.98;  // horizontal and vertical
constexpr double kT3 = 0.98;  // the two diagonals

}  // namespace

TextureClasses ClassifyTexture(const QuadrantMeans& m) {
  const double a1 = m.top_left, a2 = m.top_right, a3 = m.bottom_left, a4 = m.bottom_right;
  const double r = std::sqrt(2.0);
  // The reference's mask expressions, zero terms included (adding +0.0 changes nothing).
  const double mask[5] = {
      std::fabs(a1 * 2 + a2 * -2 + a3 * -2 + a4 * 2),
      std::fabs(a1 * 1 + a2 * 1 + a3 * -1 + a4 * -1),
      std::fabs(a1 * 1 + a2 * -1 + a3 * 1 + a4 * -1),
      std::fabs(a1 * r + a2 * 0 + a3 * 0 + a4 * -r),
      std::fabs(a1 * 0 + a2 * r + a3 * -r + a4 * 0),
  };
  const double max = *std::max_element(mask, mask + 5);

  TextureClasses result;
  if (max < kT0) {
    result.classes[result.count++] = 0;
    return result;
  }
  const double threshold[5] = {kT1, kT2, kT2, kT3, kT3};
  for (int i = 0; i < 5; ++i) {
    // mask / max > threshold, decided without the division when the margin is clear (the
    // products below are exact to far better than 1e-9 relative), else with the reference's own
    // division. Stored unconditionally and counted, to keep the loop free of branches.
    const double scaled = threshold[i] * max;
    const bool above = mask[i] > scaled * (1 + 1e-9)   ? true
                       : mask[i] < scaled * (1 - 1e-9) ? false
                                                       : mask[i] / max > threshold[i];
    result.classes[result.count] = i + 1;
    result.count += above;
  }
  return result;
}

}  // namespace orbit::cedd
