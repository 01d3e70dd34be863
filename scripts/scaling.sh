#!/usr/bin/env bash
# Measures the tables of docs/scaling.md: throughput and round trips of 1, 2 and 3 `orbit serve`
# replicas on one PostgreSQL store behind HAProxy (docker/haproxy.cfg), against one replica
# reached directly, and how long a change committed through one replica takes to reach the
# others' indexes (their orbit_model_change_lag_seconds), with and without load.
#
#   scripts/scaling.sh [BUILD_DIR]      # default build/ (./scripts/build.sh, Release)
#
# A private PostgreSQL server (BUILD_DIR/orbit_test_postgres, unix socket in $OUT/pg), COIL-100
# imported through replica 1 (about a minute), then for N = 1, 2, 3 replicas: HAProxy in front
# of replicas 1..N and one `orbit loadtest` per row, $DURATION seconds each. Everything shares
# this machine's cores: the generator, HAProxy, the replicas and PostgreSQL.
#
# Environment: ORBIT_DATA (default ../shared/data), DURATION (15), PORT (50251: the balancer;
# replicas PORT+1.., metrics PORT+11..), OUT (BUILD_DIR/scaling/<time>).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-build}
orbit="$build/orbit"
data=${ORBIT_DATA:-../shared/data}
duration=${DURATION:-15}
port=${PORT:-50251}
out=${OUT:-$build/scaling/$(date -u +%Y%m%dT%H%M%SZ)}
[ -x "$orbit" ] && [ -x "$build/orbit_test_postgres" ] || { echo "build first (./scripts/build.sh)" >&2; exit 1; }
for tool in jq haproxy curl; do
  command -v "$tool" >/dev/null || { echo "$tool is needed (apt-get install $tool)" >&2; exit 1; }
done
mkdir -p "$out"
out=$(cd "$out" && pwd)  # absolute: the PostgreSQL server runs as another user, elsewhere

pids=()
balancer=
cleanup() {
  [ -n "$balancer" ] && kill "$balancer" 2>/dev/null || true
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  "$build/orbit_test_postgres" stop "$out/pg" >/dev/null 2>&1 || true
}
trap cleanup EXIT

"$build/orbit_test_postgres" start "$out/pg" >&2
store="host=$out/pg user=orbit dbname=postgres"

wait_for() {  # wait_for LOG TEXT
  for _ in $(seq 300); do grep -qs "$2" "$1" && return 0; sleep 0.1; done
  echo "no '$2' in $1:" >&2; cat "$1" >&2; exit 1
}

start_replica() {  # start_replica I
  local i=$1
  "$orbit" serve --store "$store" --listen "127.0.0.1:$((port + i))" \
    --metrics-listen "127.0.0.1:$((port + 10 + i))" --max-fps 1000000 --max-sessions 1000 \
    2>"$out/replica-$i.log" &
  pids+=($!)
  wait_for "$out/replica-$i.log" "listening on"
}

start_balancer() {  # start_balancer N
  local n=$1 slot
  for slot in 1 2 3; do
    if (( slot <= n )); then export "ORBIT_REPLICA_$slot=127.0.0.1:$((port + slot))"
    else export "ORBIT_REPLICA_$slot=127.0.0.1:1"; fi
  done
  ORBIT_BALANCER_LISTEN="127.0.0.1:$port" haproxy -f docker/haproxy.cfg -db 2>"$out/haproxy-$n.log" &
  balancer=$!
  for _ in $(seq 100); do "$orbit" info --server "127.0.0.1:$port" --timeout 1 >/dev/null 2>&1 && break; sleep 0.1; done
  sleep 3  # the unused slots' first checks fail: every stream then goes to a live replica
}

stop_balancer() { kill "$balancer"; wait "$balancer" 2>/dev/null || true; balancer=; }

run() {  # run NAME ADDRESS LOADTEST-ARGS...
  local name=$1 address=$2
  shift 2
  echo "== $name: $* ($(uptime | sed 's/.*load average: //'))" >&2
  "$orbit" loadtest --json --server "$address" --data "$data/coil-100" --duration "$duration" \
    --engine hmm "$@" >"$out/$name.json"
}

# Lag histogram of replica I, cumulative: lines "le count".
lag_buckets() {
  curl -s "http://127.0.0.1:$((port + 10 + $1))/metrics" |
    sed -n 's/^orbit_model_change_lag_seconds_bucket{le="\([^"]*\)"} \([0-9.e+]*\)$/\1 \2/p'
}

start_replica 1
echo "importing COIL-100 through replica 1 ..." >&2
"$orbit" import --server "127.0.0.1:$((port + 1))" --layout coil100 --data "$data/coil-100" >/dev/null

run direct-1-closed "127.0.0.1:$((port + 1))" --sessions 64 --closed-loop
run direct-1-open "127.0.0.1:$((port + 1))" --sessions 256 --rate 10
for n in 1 2 3; do
  (( n > 1 )) && start_replica "$n"
  start_balancer "$n"
  run "balanced-$n-closed" "127.0.0.1:$port" --sessions 64 --closed-loop
  run "balanced-$n-open" "127.0.0.1:$port" --sessions 256 --rate 10
  for i in $(seq "$n"); do lag_buckets "$i" >"$out/lag-$n-$i.before"; done
  run "balanced-$n-enroll" "127.0.0.1:$port" --sessions 64 --rate 10 --enroll-every 1
  for i in $(seq "$n"); do lag_buckets "$i" >"$out/lag-$n-$i.after"; done
  stop_balancer
done

echo "Commit $(git rev-parse --short HEAD), $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')), PostgreSQL 15 and HAProxy $(haproxy -v | sed -n '1s/HAProxy version \([^ ]*\).*/\1/p') on the same machine, $duration s per row; JSON and logs in $out."
echo
echo "| replicas | path | load | frames/s | x one replica | RTT p50 (ms) | p90 | p99 | max | errors |"
echo "| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
base=$(jq '.frames_per_second' "$out/balanced-1-closed.json")
for name in direct-1-closed direct-1-open balanced-1-closed balanced-1-open balanced-1-enroll \
            balanced-2-closed balanced-2-open balanced-2-enroll \
            balanced-3-closed balanced-3-open balanced-3-enroll; do
  n=${name#*-}; n=${n%%-*}
  path=balancer; [[ $name == direct-* ]] && path=direct
  jq -r --arg n "$n" --arg path "$path" --argjson base "$base" '
    def mode: if .config.mode == "open-loop" then "\(.config.rate_per_session) fps" else "closed" end;
    def errors: if (.errors | length) == 0 then "0" else (.errors | to_entries | map("\(.key) \(.value)") | join(", ")) end;
    def enrollments: if .enrollments then " + \(.enrollments.done) enrollments" else "" end;
    def ratio: if .config.mode == "open-loop" then "-" else ((.frames_per_second / $base * 100 | round) / 100 | tostring) end;
    "| \($n) | \($path) | \(.config.sessions) x \(mode)\(enrollments) | \(.frames_per_second) | \(ratio) | \(.rtt_ms.p50) | \(.rtt_ms.p90) | \(.rtt_ms.p99) | \(.rtt_ms.max) | \(errors) |"
  ' "$out/$name.json"
done

echo
echo "Delay from a change's commit (through whichever replica the balancer chose) to another"
echo "replica's index, during the enrollment rows (orbit_model_change_lag_seconds; a percentile is"
echo "the upper bound of the histogram bucket it falls in):"
echo
echo "| replicas | changes followed | p50 (ms) | p99 (ms) | max bucket (ms) |"
echo "| ---: | ---: | ---: | ---: | ---: |"
for n in 2 3; do
  paste -d' ' <(cat "$out"/lag-$n-*.before | sort -g -k1,1 | awk '{c[$1]+=$2} END {for (k in c) print k, c[k]}' | sort -g) \
              <(cat "$out"/lag-$n-*.after | sort -g -k1,1 | awk '{c[$1]+=$2} END {for (k in c) print k, c[k]}' | sort -g) |
    awk -v n="$n" '
      { le[NR] = $1; count[NR] = $4 - $2 }
      END {
        total = count[NR]
        p50 = p99 = top = "-"
        for (i = 1; i <= NR; i++) {
          if (p50 == "-" && count[i] >= 0.5 * total) p50 = le[i]
          if (p99 == "-" && count[i] >= 0.99 * total) p99 = le[i]
          if (top == "-" && count[i] == total) top = le[i]
        }
        printf "| %d | %d | %s | %s | %s |\n", n, total, (p50 == "+Inf" ? p50 : p50 * 1000), (p99 == "+Inf" ? p99 : p99 * 1000), (top == "+Inf" ? top : top * 1000)
      }'
done
