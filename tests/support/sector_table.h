// Whether a snapshot already holds an HMM sector table (core/engines/sector_similarity_table.h),
// for tests of who builds it and when.
#pragma once

#include <memory>

#include "core/engines/sector_similarity_table.h"
#include "core/index/view_index.h"

namespace orbit::testing {

// Whether `snapshot` already holds the sector table for `states`: asking for it builds nothing.
inline bool HoldsSectorTable(const ViewIndexSnapshot& snapshot, int states) {
  bool built = false;
  snapshot.Derived({SectorSimilarityTable::kDerivedName, states}, [&built] {
    built = true;
    return std::make_shared<const int>(0);
  });
  return !built;
}

}  // namespace orbit::testing
