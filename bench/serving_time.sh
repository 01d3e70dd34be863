#!/usr/bin/env bash
# How long `orbit serve` takes to serve a store, and the memory it then holds:
#
#   bench/serving_time.sh BUILD STORE [SERVE_ARGS...]
#
# Starts BUILD/orbit serve on the SQLite store STORE (a copy of nothing: the server opens it as
# it is), asks it `orbit info` every 0.2 s until it answers (the server listens at once and
# answers once its index is loaded and calibrated: docs/service.md, health), then prints
# the seconds from start to that answer, the objects and views it holds, and its resident memory
# (VmRSS) and peak (VmHWM) at that moment, as one line of a table:
#
#   | objects | views | SERVING after | RSS | peak RSS |
#
# Gives up after 600 s with the server's log.
set -euo pipefail
if [[ $# -lt 2 || $1 == -h || $1 == --help ]]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
build=$1 store=$2
shift 2
[[ -f "$store" ]] || { echo "serving_time.sh: no store $store" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/serve_in_background.sh
source "$here/serve_in_background.sh"
log=$(mktemp)
trap 'kill "$server_pid" 2>/dev/null || true; rm -f "$log"' EXIT

start=$(date +%s.%N)
serve_wait_seconds=600  # a large store's server may say where it listens only once it has loaded
serve_in_background "$build/orbit" "$log" --db "$store" "$@"
answer=""
for _ in $(seq 3000); do
  if answer=$("$build/orbit" info --json --server "$address" 2>/dev/null); then break; fi
  answer=""
  sleep 0.2
done
serving=$(date +%s.%N)
if [[ -z "$answer" ]]; then
  echo "serving_time.sh: the server did not answer in 600 s:" >&2
  cat "$log" >&2
  exit 1
fi
kib() { sed -n "s/^$1:[[:space:]]*\([0-9]*\) kB/\1/p" "/proc/$server_pid/status"; }
rss=$(kib VmRSS) peak=$(kib VmHWM)
# The first "objects" and "views" of the answer are the server's own (docs/service.md, ServerInfo).
field() { echo "$answer" | grep -o "\"$1\": *[0-9]*" | head -1 | grep -o '[0-9]*$'; }
printf '| %s | %s | %s s | %d MiB | %d MiB |\n' "$(field objects)" "$(field views)" \
  "$(awk -v a="$start" -v b="$serving" 'BEGIN { printf "%.1f", b - a }')" $((rss / 1024)) \
  $((peak / 1024))
