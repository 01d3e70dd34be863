// Running a computation on both paths of the hot loops (core/base/cpu_dispatch.h) and comparing
// its results exactly, as text: the descriptors' test (tests/core/base/cpu_dispatch_test.cc) and
// the index's and engines' (tests/core/engines/engine_registry_test.cc).
#pragma once

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/base/cpu_dispatch.h"

namespace orbit::testing {

// A double written exactly (hexadecimal significand), so that equal text means equal bits.
inline std::string Exact(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

// compute() on the portable path, then on the fastest; the fastest stays active afterwards.
template <typename Compute>
std::pair<std::vector<std::string>, std::vector<std::string>> OnBothPaths(Compute compute) {
  TEST_SetHotLoopPath(HotLoopPath::kPortable);
  std::vector<std::string> portable = compute();
  TEST_SetHotLoopPath(HotLoopPath::kFastest);
  std::vector<std::string> fastest = compute();
  return {portable, fastest};
}

inline void ExpectEqualLines(const std::vector<std::string>& portable,
                             const std::vector<std::string>& fastest) {
  ASSERT_EQ(portable.size(), fastest.size());
  for (std::size_t i = 0; i < portable.size(); ++i) {
    EXPECT_EQ(portable[i], fastest[i]) << "line " << i << " differs between the paths";
  }
}

}  // namespace orbit::testing
