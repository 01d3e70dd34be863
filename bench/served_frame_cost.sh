#!/usr/bin/env bash
# What a frame costs a server as its catalogue grows, in the store's own variant:
#
#   bench/served_frame_cost.sh BUILD ROUNDS STORE...
#
# For each of ROUNDS rounds and each STORE in turn (SQLite stores, served as they are: the load
# enrolls nothing), starts BUILD/orbit serve on it, waits until `orbit info` answers (the index
# loaded and calibrated), then runs one `orbit loadtest` of 8 closed-loop sessions for DURATION
# seconds (15 unless set) showing COIL-100's views (ORBIT_DATA, ../shared/data by default), the
# server on CPU 0 and the generator on CPU 1 when there are two. Prints one table row per run:
#
#   | round | store | objects | frames/s | server CPU per frame | processing p50 | RSS |
#
# the server's CPU per frame (us) and its own processing time's median (us, as its updates state
# it) are what the catalogue's size moves; stores alternate so that each round's rows share the
# machine's minutes (docs/results/scale.md, "A served frame in the product's variant").
set -euo pipefail
if [[ $# -lt 3 || $1 == -h || $1 == --help ]]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
build=$1 rounds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/serve_in_background.sh
source "$here/serve_in_background.sh"
data=${ORBIT_DATA:-../shared/data}
work=$(mktemp -d)
trap 'kill "${server_pid:-}" 2>/dev/null || true; rm -rf "$work"' EXIT
server_cpu=() load_cpu=()
if [[ $(nproc) -ge 2 ]]; then server_cpu=(taskset -c 0) load_cpu=(taskset -c 1); fi
# serve_in_background runs one program: the server's, pinned when there are two CPUs.
printf '#!/bin/sh\nexec %s "%s/orbit" "$@"\n' "${server_cpu[*]}" "$build" >"$work/orbit"
chmod +x "$work/orbit"
serve_wait_seconds=600 # a large store's server says where it listens only once it has loaded

echo "| round | store | objects | frames/s | server CPU per frame | processing p50 | RSS |"
echo "|---|---|---|---|---|---|---|"
for round in $(seq "$rounds"); do
  for store in "$@"; do
    [[ -f "$store" ]] || { echo "served_frame_cost.sh: no store $store" >&2; exit 1; }
    serve_in_background "$work/orbit" "$work/serve.log" --db "$store" --max-fps 1000000
    objects=""
    for _ in $(seq 3000); do
      objects=$("$build/orbit" info --server "$address" 2>/dev/null |
        sed -n 's/^objects *\([0-9]*\).*/\1/p' | head -1) && [[ -n "$objects" ]] && break
      sleep 0.2
    done
    "${load_cpu[@]}" "$build/orbit" loadtest --server "$address" --data "$data/coil-100" \
      --sessions 8 --closed-loop --duration "${DURATION:-15}" --server-pid "$server_pid" \
      --json >"$work/load.json" 2>"$work/load.err" ||
      { echo "orbit loadtest failed:" >&2; cat "$work/load.err" >&2; exit 1; }
    kill "$server_pid"
    wait "$server_pid" 2>/dev/null || true
    jq -r --arg round "$round" --arg store "$(basename "$store")" --arg objects "$objects" \
      '"| \($round) | \($store) | \($objects) | \(.frames_per_second) | \(.server.cpu_us_per_frame) us | \(.server.processing_time_us.p50) us | \(.server.rss_mb_end) MB |"' \
      "$work/load.json"
  done
done
