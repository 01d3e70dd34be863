// Hot loops: the few loops that touch every pixel, view or state, each written once in plain
// C++ and run through RunHotLoop (docs/design.md#hot-loops).
//
//   ORBIT_HOT_LOOP void AddRow(const std::uint8_t* __restrict row, std::uint16_t* acc, int n) {
//     for (int i = 0; i < n; ++i) acc[i] += row[i];
//   }
//   RunHotLoop<AddRow>(row, acc, n);
//
// The portable path is the loop compiled for the target's baseline: what every platform runs,
// and on arm64 already vectorised with NEON, which every arm64 CPU has. On x86-64 the loop is
// also compiled for AVX2, and RunHotLoop runs that copy when the CPU has AVX2 (decided once per
// process). The paths give bit-identical results: the loops are integer arithmetic or float
// operations in a fixed order, and no path fuses a multiply and an add (docs/design.md#exactness).
//
// The dispatch is explicit rather than the compiler's load-time function multi-versioning,
// which ARM compilers refuse for x86 targets, breaks ThreadSanitizer, and cannot be switched,
// so a test could not compare the paths in one process.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ORBIT_HAS_AVX2_PATH 1
#else
#define ORBIT_HAS_AVX2_PATH 0
#endif

// Before a hot loop's return type: inlined into each path that runs it, so that each path's
// compiler target vectorises it.
#define ORBIT_HOT_LOOP [[gnu::always_inline]] inline

namespace orbit {

enum class HotLoopPath {
  kPortable,  // the loops compiled for the target's baseline
  kFastest,   // the fastest this CPU runs: AVX2 where it has it, else the portable path
};

// Which path RunHotLoop takes in this process; kFastest unless a test chose otherwise.
HotLoopPath ActiveHotLoopPath();

// Test only: makes RunHotLoop (and the index's intrinsic loops) take `path` from now on. Call
// it while no hot loop runs; tests use it to compare the paths (tests/core/base/
// cpu_dispatch_test.cc).
void TEST_SetHotLoopPath(HotLoopPath path);

namespace internal {

// True when RunHotLoop runs the AVX2 copies: the CPU has AVX2 and kFastest is active.
bool RunsAvx2();

#if ORBIT_HAS_AVX2_PATH
template <auto Loop, class... Args>
__attribute__((target("avx2"))) auto RunAvx2(Args... args) {
  return Loop(args...);
}
#endif

}  // namespace internal

// Loop(args...) on the active path (see the top of this file). Loop is an ORBIT_HOT_LOOP
// function.
template <auto Loop, class... Args>
inline auto RunHotLoop(Args... args) {
#if ORBIT_HAS_AVX2_PATH
  if (internal::RunsAvx2()) return internal::RunAvx2<Loop>(args...);
#endif
  return Loop(args...);
}

}  // namespace orbit
