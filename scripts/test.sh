#!/usr/bin/env bash
# Sets up, builds and runs every test. Needs the shared data at ../shared/data (or $ORBIT_DATA).
# Then fuzzes each target of fuzz/ for 10 s from its seeds: libFuzzer with ASan and UBSan, built
# with clang into build-fuzz/ (only the libraries the targets use; fuzz/CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
(cd build && ctest --output-on-failure --parallel "$(nproc)" --timeout 900)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DORBIT_FUZZ=ON >/dev/null
cmake --build build-fuzz --parallel "$(nproc)"
cd build-fuzz
ctest --output-on-failure --parallel "$(nproc)"
