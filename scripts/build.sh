#!/usr/bin/env bash
# Configures and builds Orbit (Release) into build/. Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="${ORBIT_BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build build --parallel "$(nproc)"
