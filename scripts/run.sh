#!/usr/bin/env bash
# Sets up, builds and runs the product's main job: the recognition server on loopback, with its
# embedded SQLite model store (var/models.db unless ORBIT_DB says otherwise). Extra arguments go
# to `orbit serve` (see `build/orbit serve --help`). Stop it with Ctrl-C.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
db="${ORBIT_DB:-var/models.db}"
mkdir -p "$(dirname "$db")"
exec ./build/orbit serve --db "$db" --listen "${ORBIT_LISTEN:-127.0.0.1:50051}" "$@"
