// The texture half of CEDD (docs/design.md#texture-of-a-block): the five MPEG-7 edge-filter
// magnitudes of a block's four quadrant means, and the texture classes they select.
#pragma once

#include <array>

namespace orbit::cedd {

// Truncated quadrant means (integers kept as doubles, as the reference keeps them).
struct QuadrantMeans {
  double top_left = 0, top_right = 0, bottom_left = 0, bottom_right = 0;
};

// The classes a block belongs to, in detection order: either {0} (non-edge), or a non-empty
// subset of 1..5 (non-directional, horizontal, vertical, 45, 135) in increasing order.
struct TextureClasses {
  std::array<int, 5> classes{};
  int count = 0;
};

TextureClasses ClassifyTexture(const QuadrantMeans& means);

}  // namespace orbit::cedd
