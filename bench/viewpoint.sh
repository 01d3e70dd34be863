#!/usr/bin/env bash
# Recognition from above the enrolled ring, end to end (docs/results/real-objects.md, "Views
# from above the ring"). eth-80-dev's ring views (ring.csv: elevation 0, every 22.5 degrees) are
# imported into a fresh SQLite store, which `orbit serve` serves with the product's defaults.
# Then, for every object and each ELEVATION, `orbit recognize` sends the object's views at that
# elevation (all.csv) four at a time in azimuth order, with their azimuths, as a device walking
# round the object higher up would: whole frames, then each frame cut to its box (boxes.csv,
# grown by 10% a side). Prints, per elevation and mode, how many of the queries' last updates
# name the right object first, and how many of those are accepted, after the variant served.
#   bench/viewpoint.sh [BUILD_DIR] [ETH80_DIR] [ELEVATIONS] [OBJECTS] [VARIANT]
# ELEVATIONS: comma-separated (default 22,24,45; 0 is the ring itself); OBJECTS: how many of the
# 40, in ring.csv's order, are enrolled and queried (default all); VARIANT: the stores' descriptor
# variant (default the product's), which the server then serves.
set -euo pipefail
build=${1:-build}
data=${2:-../shared/data/eth-80-dev}
elevations=${3:-22,24,45}
max_objects=${4:-40}
variant=()
[[ -n ${5:-} ]] && variant=(--variant "$5")
orbit="$build/orbit"
work=$(mktemp -d)
# shellcheck source=bench/serve_in_background.sh
source "$(dirname "$0")/serve_in_background.sh"
trap 'kill "${server_pid:-}" 2>/dev/null || true; rm -rf "$work"' EXIT

data=$(realpath "$data")
# The boxes of the ring's views, their paths made absolute (a CSV's relative paths are read
# from its own folder).
awk -F, -v d="$data" 'NR == FNR { if (FNR > 1) ring[$1] = 1; next }
  FNR == 1 || ($1 in ring) { if (FNR > 1) $1 = d "/" $1; print }' OFS=, \
  "$data/ring.csv" "$data/boxes.csv" >"$work/ring-boxes.csv"
objects=$(awk -F, 'NR > 1 { print $2 }' "$data/ring.csv" | awk '!seen[$0]++' | head -n "$max_objects")
# The ring's views of those objects.
awk -F, -v d="$data" -v list="$(tr '\n' ' ' <<<"$objects")" '
  BEGIN { n = split(list, names, " "); for (i = 1; i <= n; ++i) keep[names[i]] = 1 }
  FNR == 1 || ($2 in keep) { if (FNR > 1) $1 = d "/" $1; print }' OFS=, \
  "$data/ring.csv" >"$work/ring.csv"
IFS=, read -r -a wanted <<<"$elevations"
for mode in whole cropped; do
  # The models: the ring's views, whole or cut to their boxes as the queries are.
  enrolled=()
  [[ $mode == cropped ]] && enrolled=(--boxes "$work/ring-boxes.csv")
  "$orbit" import --db "$work/$mode.db" --layout manifest --manifest "$work/ring.csv" \
    "${enrolled[@]}" "${variant[@]}" >/dev/null 2>"$work/import.log" || { cat "$work/import.log" >&2; exit 1; }
  serve_in_background "$orbit" "$work/serve.log" --db "$work/$mode.db"
  # The variant the server took from the store.
  sed -n "s/^orbit serve: \(descriptor variant [^ ]*\).*/$mode: served \1/p" "$work/serve.log"
  for elevation in "${wanted[@]}"; do
    queries=0 right=0 accepted=0
    for object in $objects; do
      # The object's views at this elevation, in azimuth order: path azimuth x,y,w,h.
      awk -F, -v o="$object" -v e="$elevation" '
        NR == FNR { if (FNR > 1) box[$1] = $2 "," $3 "," $4 "," $5; next }
        FNR > 1 && $2 == o && $4 == e { print $1, $3, box[$1] }' \
        "$data/boxes.csv" "$data/all.csv" | sort -k2,2n >"$work/views"
      mapfile -t views <"$work/views"
      for ((first = 0; first + 4 <= ${#views[@]}; first += 4)); do
        args=()
        for ((k = first; k < first + 4; ++k)); do
          read -r path azimuth box <<<"${views[k]}"
          args+=(--image "$data/$path" --azimuth "$azimuth")
          [[ $mode == cropped ]] && args+=(--box "$box")
        done
        last=$("$orbit" recognize --server "$address" --json --top-k 1 "${args[@]}" | tail -1)
        queries=$((queries + 1))
        if [[ $last == *"\"candidates\":[{\"id\":"*",\"name\":\"$object\""* ]]; then
          right=$((right + 1))
          [[ $last == *'"decision":"ACCEPT"'* ]] && accepted=$((accepted + 1))
        fi
      done
    done
    awk -v e="$elevation" -v m="$mode" -v q="$queries" -v r="$right" -v a="$accepted" \
      'BEGIN { printf "elevation %-3s %-8s right %5.1f%% (%d/%d), right and accepted %5.1f%%\n", e, m, 100 * r / q, r, q, 100 * a / q }'
  done
  kill "$server_pid"
  wait "$server_pid" 2>/dev/null || true
done
