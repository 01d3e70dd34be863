#!/usr/bin/env bash
# Hit rate from generated walks (docs/results/capture.md): objects FIRST..LAST of COIL-100 are
# each enrolled from a walk round them (`orbit walk`: 72 frames, clutter, blurred and noisy
# frames, a noisy drifting compass) and recognised from a second walk on another background
# (24 frames from azimuth 100, 120 degrees), twice: with the object's box tracked from the first
# frame (--box), and with the true box of every frame given (--boxes). Prints, for each, the
# share of updates whose first candidate is the right object, how many updates were accepted
# naming the right object and naming another, of final updates that are right, the views
# enrolled and the frames the tracker lost. VARIANT is the server's descriptor variant
# (`orbit serve --variant`; the product's by default).
# TRACKER=name follows the box with that tracker (`--tracker`) instead of the default;
# OBJECTS="3 8 ..." takes those objects instead of FIRST..LAST. Each object's own line follows
# its walk: updates whose first candidate is right, accepted right and accepted wrong.
#   bench/capture_hit_rate.sh [BUILD_DIR] [COIL_DIR] [FIRST] [LAST] [VARIANT]
set -euo pipefail
build=${1:-build}
coil=${2:-../shared/data/coil-100}
first=${3:-1}
last=${4:-20}
variant=()
[[ -n ${5:-} ]] && variant=(--variant "$5")
tracker=()
[[ -n ${TRACKER:-} ]] && tracker=(--tracker "$TRACKER")
objects_list=${OBJECTS:-$(seq "$first" "$last")}
orbit="$build/orbit"
work=$(mktemp -d)
# shellcheck source=bench/serve_in_background.sh
source "$(dirname "$0")/serve_in_background.sh"
trap 'kill "${server_pid:-}" 2>/dev/null || true; rm -rf "$work"' EXIT

for mode in tracked true; do
  serve_in_background "$orbit" "$work/serve.log" --db "$work/$mode.db" "${variant[@]}"
  views=0 lost=0 right=0 updates=0 final_right=0 objects=0 accepted_right=0 accepted_wrong=0
  for object in $objects_list; do
    for walk in enroll query; do
      if [[ $walk == enroll ]]; then shape="--frames 72 --seed 1"; else
        shape="--frames 24 --turn 120 --start 100 --seed 7"; fi
      # shellcheck disable=SC2086
      box=$("$orbit" walk --coil "$coil" --object "$object" --video "$work/$walk.avi" \
        --orientation "$work/$walk.csv" --boxes "$work/$walk.boxes" $shape | sed 's/.*first box //')
      if [[ $mode == tracked ]]; then where=(--box "$box" "${tracker[@]}"); else where=(--boxes "$work/$walk.boxes"); fi
      if [[ $walk == enroll ]]; then
        out=$("$orbit" enroll --server "$address" --name "obj$object" --video "$work/$walk.avi" \
          --orientation "$work/$walk.csv" "${where[@]}" 2>"$work/err") ||
          { echo "enroll obj$object ($mode) failed:" >&2; cat "$work/err" >&2; exit 1; }
        views=$((views + $(sed -n 's/.*, \([0-9]*\) views).*/\1/p' <<<"$out")))
        lost=$((lost + $(sed -n 's/.*frames, \([0-9]*\) lost.*/\1/p' <<<"$out")))
      fi
    done
  done
  for object in $objects_list; do
    box=$("$orbit" walk --coil "$coil" --object "$object" --video "$work/query.avi" \
      --orientation "$work/query.csv" --boxes "$work/query.boxes" --frames 24 --turn 120 \
      --start 100 --seed 7 | sed 's/.*first box //')
    if [[ $mode == tracked ]]; then where=(--box "$box" "${tracker[@]}"); else where=(--boxes "$work/query.boxes"); fi
    # One line per update: its decision and its first candidate ("ACCEPT obj3").
    answers=$("$orbit" recognize --server "$address" --json --fast --top-k 1 \
      --video "$work/query.avi" --orientation "$work/query.csv" "${where[@]}" 2>"$work/err" |
      sed -n 's/.*"decision":"\([A-Z]*\)".*"candidates":\[{"id":[0-9]*,"name":"\([^"]*\)".*/\1 \2/p')
    firsts=$(cut -d' ' -f2 <<<"$answers")
    n=$(wc -l <<<"$firsts")
    updates=$((updates + n))
    lost=$((lost + 24 - n))
    walk_right=$(grep -c -x "obj$object" <<<"$firsts" || true)
    walk_accepted_right=$(grep -c -x "ACCEPT obj$object" <<<"$answers" || true)
    walk_accepted_wrong=$(grep "^ACCEPT " <<<"$answers" | grep -c -v -x "ACCEPT obj$object" || true)
    echo "  obj$object ($mode): right first $walk_right/$n, accepted right $walk_accepted_right," \
      "accepted wrong $walk_accepted_wrong"
    right=$((right + walk_right))
    accepted_right=$((accepted_right + walk_accepted_right))
    accepted_wrong=$((accepted_wrong + walk_accepted_wrong))
    [[ $(tail -1 <<<"$firsts") == "obj$object" ]] && final_right=$((final_right + 1))
    objects=$((objects + 1))
  done
  kill "$server_pid"; wait "$server_pid" 2>/dev/null || true
  awk -v m="$mode" -v r="$right" -v u="$updates" -v f="$final_right" -v o="$objects" \
    -v v="$views" -v l="$lost" -v ar="$accepted_right" -v aw="$accepted_wrong" 'BEGIN { printf "%-8s updates right %5.1f%% (%d/%d), accepted right %d, accepted wrong %d, final updates right %d/%d, views enrolled %d, frames lost %d\n", m, 100*r/u, r, u, ar, aw, f, o, v, l }'
done
