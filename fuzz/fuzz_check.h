// ORBIT_FUZZ_CHECK, the checks the fuzz targets of this folder make beyond "no crash". Each
// target is one *_fuzzer.cc defining LLVMFuzzerTestOneInput.
#pragma once

#include <cstdio>
#include <cstdlib>

// A property the code promises, checked on every input: when it fails, the target aborts, which
// libFuzzer (and the replay driver) report as a crash with this message.
#define ORBIT_FUZZ_CHECK(condition)                                                           \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::fprintf(stderr, "%s:%d: fuzz check failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                           \
    }                                                                                         \
  } while (false)
