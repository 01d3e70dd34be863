#!/usr/bin/env bash
# Sets up, builds and runs every test. Needs the shared data at ../shared/data (or $ORBIT_DATA).
# First, the layout: every C++ file as .clang-format lays it out (scripts/format.sh --check).
# Before the tests, the lock rules: the libraries built with clang's thread safety analysis, its
# findings errors (ORBIT_THREAD_SAFETY, core/base/mutex.h), into build-tsa/: unoptimised, and no
# test or executable, since only the compile checks anything. From a clean build-tsa/ on the
# 2-CPU development machine: 102 s with the machine otherwise idle, 218 s with other builds
# running; later runs redo only what changed.
# Then fuzzes each target of fuzz/ for 10 s from its seeds: libFuzzer with ASan and UBSan, built
# with clang into build-fuzz/ (only the libraries the targets use; fuzz/CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/format.sh --check
./scripts/build.sh
cmake -S . -B build-tsa -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
  -DORBIT_THREAD_SAFETY=ON >/dev/null
cmake --build build-tsa --parallel "$(nproc)" --target orbit_libraries
(cd build && ctest --output-on-failure --parallel "$(nproc)" --timeout 900)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DORBIT_FUZZ=ON >/dev/null
cmake --build build-fuzz --parallel "$(nproc)"
cd build-fuzz
ctest --output-on-failure --parallel "$(nproc)"
