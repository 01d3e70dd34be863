// The last step of CEDD (docs/design.md#quantisation): the 144-bin
// fuzzy histogram, normalised by its sum, each bin quantised to the nearest of its texture
// class's eight levels.
#pragma once

#include "core/descriptor/descriptor.h"

namespace orbit::cedd {

using Histogram = double[kCeddSize];

// Normalises by the sum (added in index order) and quantises each bin as LIRE's CEDDQuant does
// (nearest level, ties to the lower). An all-zero histogram (a region with no blocks) gives all
// zeros: nothing is divided by zero.
DescriptorValues Quantise(const Histogram& histogram);

}  // namespace orbit::cedd
