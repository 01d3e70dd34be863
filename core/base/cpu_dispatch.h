// ORBIT_AVX2_CLONES: a hot loop compiled for AVX2 as well as the baseline, the version chosen
// once at load time by the CPU (function multi-versioning: `target_clones`). Put it before the
// function's return type.
//
// Under ThreadSanitizer it is empty (the baseline only, identical results: no fused
// multiply-add either way). The load-time chooser is an ifunc resolver that the dynamic loader
// runs before TSan's runtime has started, and TSan's instrumentation of it crashes every
// program at start (GCC 12 and clang 14 alike; scripts/sanitize.sh tsan).
#pragma once

#if defined(__SANITIZE_THREAD__)  // GCC
#define ORBIT_AVX2_CLONES
#elif defined(__has_feature)  // clang
#if __has_feature(thread_sanitizer)
#define ORBIT_AVX2_CLONES
#endif
#endif

#ifndef ORBIT_AVX2_CLONES
#define ORBIT_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif
