#!/usr/bin/env bash
# Sets up, builds and runs every test. Needs the shared data at ../shared/data (or $ORBIT_DATA).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
