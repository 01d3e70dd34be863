#!/usr/bin/env bash
# Sets up, builds and runs the product's main job. For now: the CEDD descriptor of sample images
# from the shared data (the server arrives with the service issue).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
data="${ORBIT_DATA:-../shared/data}"
exec ./build/orbit descriptor --variant cedd-lire "$data"/coil-100/obj1__0.png "$data"/coil-100/obj42__90.png "$@"
