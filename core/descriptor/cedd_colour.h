// The colour half of CEDD (docs/design.md#colour-of-a-block): a block's mean colour becomes a
// 24-bin fuzzy colour histogram via LIRE's integer HSV, the 10-bin fuzzy linking and its
// expansion to 24 bins.
//
// Every floating-point expression is evaluated in the reference's order, so the result is
// bit-identical to LIRE's. Thread-safe.
#pragma once

#include <array>

namespace orbit::cedd {

struct Hsv {
  int h = 0;  // 0..359
  int s = 0;  // 0..255
  int v = 0;  // 0..255
};

// LIRE's RGB2HSV on integer means (note the offsets 359, 119, 239).
Hsv RgbToHsv(int red, int green, int blue);

using Fuzzy10 = std::array<double, 10>;
using Fuzzy24 = std::array<double, 24>;

// The 10-bin fuzzy linking, step 4 of docs/design.md#colour-of-a-block (white, grey, black,
// red ... magenta).
Fuzzy10 FuzzyLink10(const Hsv& hsv);

// The 24-bin expansion, step 5 of docs/design.md#colour-of-a-block (each chromatic bin split
// light/normal/dark).
Fuzzy24 FuzzyLink24(const Hsv& hsv, const Fuzzy10& fuzzy10);

// Both steps at once: the block's contribution to each of the 24 colour bins.
Fuzzy24 FuzzyColour(int red, int green, int blue);

}  // namespace orbit::cedd
