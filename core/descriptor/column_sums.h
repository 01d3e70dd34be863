// AddRowToColumnSums: the loop that reads every pixel of an image once, shared by the CEDD grid
// and the canonical frame's block means: each row's bytes added into one sum per byte position.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/base/cpu_dispatch.h"

namespace orbit {

// acc[i] += row[i] for i in [0, n): memory-bound work that the wider vectors of the fastest path
// halve (run it with RunHotLoop). Sum is std::uint16_t or std::uint32_t; REQUIRES: the caller
// adds few enough rows that no sum overflows (257 rows of 255 fit 16 bits).
template <typename Sum>
ORBIT_HOT_LOOP void AddRowToColumnSums(const std::uint8_t* __restrict row, Sum* __restrict acc,
                                       std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) acc[i] = static_cast<Sum>(acc[i] + row[i]);
}

}  // namespace orbit
