#!/usr/bin/env bash
# Measures the load table of docs/results/load.md with `orbit loadtest` and prints it as Markdown;
# or, with `soak`, runs the soak of docs/results/load.md and prints its summary.
#
#   scripts/loadtest.sh [BUILD_DIR]        # default build/, which ./scripts/build.sh makes (Release)
#   scripts/loadtest.sh BUILD_DIR soak     # 500 sessions x 10 frames/s for SOAK_SECONDS (600), an
#                                          # enrollment every 3 s and the one before it deleted
#   OBJECTS=1000 scripts/loadtest.sh       # the 1000-object rows (the goals at 1000 objects)
#
# A server (`orbit serve`, pinned to CPU $SERVER_CPU) on a copy of a SQLite store holding all 100
# COIL-100 objects (imported once into $DB), then one `orbit loadtest` (pinned to
# CPU $LOAD_CPU) per row, $DURATION seconds each, in the order of the table. Every run's JSON goes
# to $OUT; the Markdown table to stdout, progress to stderr. With OBJECTS=1000 the store holds
# COIL-100 and nine copies of it with permuted colours and turned images (BUILD_DIR/
# orbit_coil_variants; 1000 objects x 72 views, made once), and the sessions
# show the 100 original objects.
#
# Environment: ORBIT_DATA (default ../shared/data), DURATION (15), PORT (50151), SERVER_CPU (0),
# LOAD_CPU (1), OBJECTS (100 or 1000), CONNECTIONS (one: every session of a row on one TCP
# connection, as ghz does; each: a connection per session, as separate devices would have), DB
# (BUILD_DIR/loadtest/coil<OBJECTS>.db), OUT (BUILD_DIR/loadtest/<time>), COMMIT (the commit
# BUILD_DIR was built from, for the table's heading; default the checkout's HEAD), SERVE_FLAGS
# (more flags for `orbit serve`, e.g. "--candidates-above 5000"; default none).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-build}
mode=${2:-table}
[[ "$mode" == table || "$mode" == soak ]] || { echo "usage: $0 [BUILD_DIR] [soak]" >&2; exit 2; }
orbit="$build/orbit"
data=${ORBIT_DATA:-../shared/data}
duration=${DURATION:-15}
port=${PORT:-50151}
server_cpu=${SERVER_CPU:-0}
load_cpu=${LOAD_CPU:-1}
objects=${OBJECTS:-100}
connections=${CONNECTIONS:-one}
[[ "$connections" == one || "$connections" == each ]] || { echo "CONNECTIONS must be one or each" >&2; exit 2; }
[[ "$objects" == 100 || "$objects" == 1000 ]] || { echo "OBJECTS must be 100 or 1000" >&2; exit 2; }
db=${DB:-$build/loadtest/coil$objects.db}
out=${OUT:-$build/loadtest/$(date -u +%Y%m%dT%H%M%SZ)}

[ -x "$orbit" ] || { echo "no $orbit: build first (./scripts/build.sh)" >&2; exit 1; }
build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
[ "$build_type" = Release ] || echo "warning: $build is a '$build_type' build, not Release" >&2
command -v jq >/dev/null || { echo "jq is needed to read the reports (apt-get install jq)" >&2; exit 1; }
mkdir -p "$out" "$(dirname "$db")"

if [ ! -f "$db" ]; then
  images=$data/coil-100
  if [[ "$objects" == 1000 ]]; then
    images=$build/loadtest/coil1000-images
    [ -x "$build/orbit_coil_variants" ] || { echo "no $build/orbit_coil_variants: build first" >&2; exit 1; }
    echo "writing COIL-100 x 10 (1000 objects x 72 views) into $images ..." >&2
    "$build/orbit_coil_variants" "$data/coil-100" "$images" 10
  fi
  echo "importing $objects objects x 72 views into $db ..." >&2
  "$orbit" import --db "$db.partial" --layout coil100 --data "$images" >/dev/null
  mv "$db.partial" "$db"
  if [[ "$objects" == 1000 ]]; then rm -rf "$images"; fi
fi
# The server works on a copy: the enrollments of the last row are deleted afterwards, but ids and
# the file's pages would still drift from run to run.
cp "$db" "$out/models.db"

# --max-fps: a closed-loop session sends thousands of frames per second, far above the default 60.
# --max-sessions: the soak opens 500. --max-streams-per-connection: with CONNECTIONS=one every
# session of a row is a call on one connection, and the default (100 calls) would hold the
# sessions beyond it until others end, their frames' round trips counted from when they were due.
taskset -c "$server_cpu" "$orbit" serve --db "$out/models.db" --listen "127.0.0.1:$port" \
  --max-fps 1000000 --max-sessions 1000 --max-streams-per-connection 1000 ${SERVE_FLAGS:-} \
  2>"$out/serve.log" &
server=$!
trap 'kill "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true' EXIT
for _ in $(seq 100); do
  grep -qs "listening on" "$out/serve.log" && break
  kill -0 "$server" 2>/dev/null || { cat "$out/serve.log" >&2; exit 1; }
  sleep 0.2
done
grep -q "listening on" "$out/serve.log" || { echo "the server did not start" >&2; exit 1; }

# run NAME ARGS...: one loadtest, its JSON in $out/NAME.json, the load average before it in
# $out/NAME.load.
run() {
  local name=$1
  shift
  if [[ "$connections" == each ]]; then
    local args=("$@") i
    for ((i = 0; i + 1 < ${#args[@]}; ++i)); do
      [[ "${args[i]}" == --sessions ]] && set -- "$@" --connections "${args[i + 1]}"
    done
  fi
  echo "== $name: $* ($(uptime | sed 's/.*load average: //'))" >&2
  uptime | sed 's/.*load average: //; s/,.*//' >"$out/$name.load"
  taskset -c "$load_cpu" "$orbit" loadtest --json --server "127.0.0.1:$port" --server-pid "$server" \
    --data "$data/coil-100" --duration "$duration" "$@" >"$out/$name.json"
}

if [[ "$mode" == soak ]]; then
  soak_seconds=${SOAK_SECONDS:-600}
  duration=$soak_seconds run soak --engine hmm --sessions 500 --rate 10 --enroll-every 3 \
    --delete-during
  echo "Soak at $(git rev-parse --short HEAD), $(nproc) CPUs, load average before: $(cat "$out/soak.load"); JSON in $out/soak.json."
  jq -r '
    "- \(.config.sessions) sessions x \(.config.rate_per_session) frames/s, \(.config.duration_s) s, \(.config.engine): \(.frames.sent) frames sent, \(.frames.answered) answered, \(.frames.unanswered) unanswered; sessions \(.sessions.opened) opened, \(.sessions.failed) failed, \(.sessions.cancelled) cancelled; errors \(.errors)",
    "- round trip p50 \(.rtt_ms.p50) ms, p99 \(.rtt_ms.p99), max \(.rtt_ms.max); worst session p99 \(.rtt_ms.worst_session_p99) ms, \(.rtt_ms.sessions_p99_above_5ms) sessions above 5 ms",
    "- \(.enrollments.done) enrollments of \(.enrollments.views) views (p50 \(.enrollments.latency_ms.p50) ms, max \(.enrollments.latency_ms.max)), \(.enrollments.deleted) deleted during the load",
    "- server CPU \(.server.cpu_us_per_frame) us per frame (\(.server.cpu_percent)% of a core); RSS (s: MB) \(.server.rss_mb_samples | map("\(.[0]): \(.[1])") | join(", "))"
  ' "$out/soak.json"
  exit 0
fi

if [[ "$objects" == 100 ]]; then
  rows=(open-64-hmm open-256-hmm closed-8-hmm closed-64-hmm closed-8-vci closed-64-vci open-1-hmm
        open-64-hmm-enroll)
  run open-64-hmm --engine hmm --sessions 64 --rate 10
  run open-256-hmm --engine hmm --sessions 256 --rate 10
  run closed-8-hmm --engine hmm --sessions 8 --closed-loop
  run closed-64-hmm --engine hmm --sessions 64 --closed-loop
  run closed-8-vci --engine vci --sessions 8 --closed-loop
  run closed-64-vci --engine vci --sessions 64 --closed-loop
  run open-1-hmm --engine hmm --sessions 1 --rate 10
  run open-64-hmm-enroll --engine hmm --sessions 64 --rate 10 --enroll-count 20
  enroll_row=open-64-hmm-enroll
else
  # The goals at 1000 objects: closed loop at 8 and 256 sessions against the engine's cost (the
  # server's processing time at one session), 256 x 10 frames/s, and the same with a 72-view
  # enrollment every 5 s (each deleted after the load).
  rows=(open-1-hmm closed-8-hmm closed-256-hmm open-256-hmm open-256-hmm-enroll)
  run open-1-hmm --engine hmm --sessions 1 --rate 10
  run closed-8-hmm --engine hmm --sessions 8 --closed-loop
  run closed-256-hmm --engine hmm --sessions 256 --closed-loop
  run open-256-hmm --engine hmm --sessions 256 --rate 10
  run open-256-hmm-enroll --engine hmm --sessions 256 --rate 10 --enroll-every 5
  enroll_row=open-256-hmm-enroll
fi

# One Markdown row per run.
row() {
  local name=$1 load
  load=$(cat "$out/$name.load")
  jq -r --arg load "$load" '
    def n(x): if x == null then "-" else (x | tostring) end;
    def mode: if .config.mode == "open-loop" then "\(.config.rate_per_session) fps" else "closed" end;
    def errors: if (.errors | length) == 0 then "0" else (.errors | to_entries | map("\(.key) \(.value)") | join(", ")) end;
    def enrollments: if .enrollments then " + \(.enrollments.done) enrollments" else "" end;
    "| \(.config.sessions) x \(mode)\(enrollments) | \(.config.engine) | \(.frames_per_second) | \(.rtt_ms.p50) | \(.rtt_ms.p90) | \(.rtt_ms.p99) | \(.rtt_ms.max) | \(.server.processing_time_us.p50) / \(.server.processing_time_us.p99) | \(n(.server.cpu_us_per_frame)) (\(n(.server.cpu_percent))%) | \(.generator.cpu_us_per_frame) (\(.generator.cpu_percent)%) | \(n(.server.rss_mb_start)) -> \(n(.server.rss_mb_end)) | \(errors) | \($load) |"
  ' "$out/$name.json"
}

if [ -n "${COMMIT:-}" ]; then
  commit=$COMMIT dirty=""
else
  commit=$(git rev-parse --short HEAD)
  dirty=$(git status --porcelain --untracked-files=no | grep -q . && echo " (working tree has uncommitted changes)" || true)
fi
sharing="every session of a row on one TCP connection"
[[ "$connections" == each ]] && sharing="a TCP connection per session"
echo "Commit $commit$dirty, $objects objects x 72 views, $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')), $duration s per row, $sharing${SERVE_FLAGS:+, orbit serve $SERVE_FLAGS}; JSON in $out."
echo
echo "| load | engine | frames/s | RTT p50 (ms) | p90 | p99 | max | server processing p50 / p99 (us) | server CPU per frame (us) | generator CPU per frame (us) | server RSS start -> end (MB) | errors | load avg before |"
echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- | ---: |"
for name in "${rows[@]}"; do
  row "$name"
done
echo
jq -r '"During \(.enrollments.done) enrollments of \(.enrollments.views) views (\(.config.sessions) x \(.config.rate_per_session) fps HMM): RTT p50 \(.enrollments.rtt_ms_during.p50) ms, p90 \(.enrollments.rtt_ms_during.p90), p99 \(.enrollments.rtt_ms_during.p99), max \(.enrollments.rtt_ms_during.max) over \(.enrollments.rtt_ms_during.count) frames; enrollment latency p50 \(.enrollments.latency_ms.p50) ms, p99 \(.enrollments.latency_ms.p99), max \(.enrollments.latency_ms.max); \(.enrollments.deleted) deleted afterwards; worst session p99 \(.rtt_ms.worst_session_p99) ms, \(.rtt_ms.sessions_p99_above_5ms) sessions above 5 ms."' \
  "$out/$enroll_row.json"
