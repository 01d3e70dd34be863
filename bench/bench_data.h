// Where the benchmarks find the shared data: $ORBIT_DATA if set, else ../shared/data beside the
// repository (as the tests do).
#pragma once

#include <filesystem>

namespace orbit::bench {

std::filesystem::path DataDir();

}  // namespace orbit::bench
