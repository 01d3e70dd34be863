#!/usr/bin/env bash
# docs/client.md's "Your own objects" runs as written: its ```sh blocks, in order, in one bash
# that stops at the first failing command, against a fresh `orbit serve` (an empty SQLite store,
# a free loopback port, no tokens: what ./scripts/run.sh starts) in place of 127.0.0.1:50051.
# Then what a user would notice: every enrollment succeeded, a walk round an enrolled car it was
# not enrolled from is answered with that car and accepted, a walk round the car never enrolled
# is answered UNKNOWN, and `orbit eval` counts that car as unknown and recognises the others.
#   tests/docs/client_your_own_objects_test.sh SOURCE_DIR BUILD_DIR DATA_DIR
# DATA_DIR: the shared data (ORBIT_DATA, else ../shared/data beside the source tree).
#
# The blocks run from a stand-in for the repository root in a temporary folder: every entry of
# SOURCE_DIR linked in, build/ linked to BUILD_DIR and ../shared/data to DATA_DIR, so the doc's
# paths resolve as from the real root while the files its commands write (captures.csv) stay
# out of the source tree.
set -euo pipefail
source_dir=$(realpath "$1")
build_dir=$(realpath "$2")
data_dir=$(realpath "$3")
work=$(mktemp -d)
# shellcheck source=bench/serve_in_background.sh
source "$source_dir/bench/serve_in_background.sh"
trap 'kill "${server_pid:-}" 2>/dev/null || true; rm -rf "$work"' EXIT

fail() {
  echo "FAIL: $*" >&2
  echo "--- the walk-through's output:" >&2
  cat "$work/out.log" >&2
  exit 1
}

# The section's sh blocks, each announced by a marker line so that its output can be told apart.
awk '/^## / { inside = ($0 == "## Your own objects"); next }
  inside && /^```sh$/ { code = 1; print "echo \"=== block " ++blocks "\""; next }
  code && /^```$/ { code = 0; next }
  code { print }' "$source_dir/docs/client.md" >"$work/doc.sh"
grep -q '^echo "=== block' "$work/doc.sh" || { echo "FAIL: no sh block in the section" >&2; exit 1; }
grep -q '127\.0\.0\.1:50051' "$work/doc.sh" ||
  { echo "FAIL: the section's commands do not name 127.0.0.1:50051" >&2; exit 1; }

mkdir -p "$work/root" "$work/shared"
for entry in "$source_dir"/*; do
  [[ $(basename "$entry") == build ]] || ln -s "$entry" "$work/root/"
done
ln -s "$build_dir" "$work/root/build"
ln -s "$data_dir" "$work/shared/data"

serve_in_background "$build_dir/orbit" "$work/serve.log" --db "$work/models.db"
# Every command goes to this server and none to a server of the same machine on the doc's port.
sed "s/127\.0\.0\.1:50051/$address/g" "$work/doc.sh" >"$work/run.sh"
touch "$work/out.log"
(cd "$work/root" && bash -e -o pipefail "$work/run.sh") >"$work/out.log" 2>&1 ||
  fail "a command of the walk-through failed"

# Enroll: the three cars, each with its views.
for car in car01 car02 car03; do
  grep -Eq "^enrolled $car \(id [0-9]+, [0-9]+ views\)$" "$work/out.log" || fail "$car not enrolled"
done

# Recognise: the last update of each session, as "DECISION FIRST-CANDIDATE" ("frame 0" starts a
# session).
awk '/^frame 0 / { ++session } /^frame [0-9]+ / {
    line = $0; sub(/ \(id [0-9]+\).*/, "", line); n = split(line, word, " ")
    last[session] = $3 " " word[n] }
  END { for (s = 1; s <= session; ++s) print last[s] }' "$work/out.log" >"$work/answers"
[[ $(sed -n 1p "$work/answers") == "ACCEPT car02" ]] ||
  fail "the walk round car02 was answered '$(sed -n 1p "$work/answers")', not 'ACCEPT car02'"
[[ $(sed -n 2p "$work/answers") == UNKNOWN\ * ]] ||
  fail "the walk round car04 was answered '$(sed -n 2p "$work/answers")', not UNKNOWN"

# Info: the three cars held.
grep -Eq '^objects +3 \(' "$work/out.log" || fail "orbit info does not show 3 objects"

# Measure: three enrolled cars, car04 counted as unknown; at n = 4, the known walks nearly all
# right and accepted and most unknown ones rejected (a number, not "-": they were counted).
grep -q '3 enrolled objects, .* 1 unknown object among the queries' "$work/out.log" ||
  fail "the eval report does not count 3 enrolled cars and 1 unknown"
row=$(grep -E '^\| server \(product\) \| [^|]+ \| DF \| 4 \|' "$work/out.log" | head -1)
[[ -n $row ]] || fail "no recognition row at n = 4 in the eval report"
IFS='|' read -r -a cell <<<"$row"
known_right=${cell[5]// /} unknown_rejected=${cell[8]// /}
awk -v k="$known_right" -v u="$unknown_rejected" \
  'BEGIN { exit !(k ~ /^[0-9.]+$/ && k >= 90 && u ~ /^[0-9.]+$/ && u >= 50) }' ||
  fail "at n = 4: known right+accepted $known_right%, unknown rejected $unknown_rejected%"
echo "walk-through ran: $(grep -c '^enrolled ' "$work/out.log") cars enrolled;" \
  "known right+accepted $known_right%, unknown rejected $unknown_rejected% at n = 4"
