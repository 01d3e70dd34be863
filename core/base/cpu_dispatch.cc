#include "core/base/cpu_dispatch.h"

#include <atomic>

namespace orbit {
namespace {

// Atomic so that a test's switch is a defined write even when a worker thread of an earlier
// test is still reading it; the paths give equal results, so a late reader is harmless.
std::atomic<HotLoopPath> active_path{HotLoopPath::kFastest};

bool CpuHasAvx2() {
#if ORBIT_HAS_AVX2_PATH
  __builtin_cpu_init();  // may run before the runtime's own initialisation (a static's)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace

HotLoopPath ActiveHotLoopPath() { return active_path.load(std::memory_order_relaxed); }

void TEST_SetHotLoopPath(HotLoopPath path) { active_path.store(path, std::memory_order_relaxed); }

namespace internal {

bool RunsAvx2() {
  static const bool has_avx2 = CpuHasAvx2();
  return has_avx2 && ActiveHotLoopPath() == HotLoopPath::kFastest;
}

}  // namespace internal
}  // namespace orbit
