#include "bench/bench_data.h"

#include <cstdlib>

namespace orbit::bench {

std::filesystem::path DataDir() {
  const char* env = std::getenv("ORBIT_DATA");
  return env != nullptr ? std::filesystem::path(env)
                        : std::filesystem::path(ORBIT_SOURCE_DIR) / ".." / "shared" / "data";
}

}  // namespace orbit::bench
