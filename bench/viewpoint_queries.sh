#!/usr/bin/env bash
# The queries of bench/viewpoint.sh as a CSV for `orbit eval --queries` (docs/results/
# real-objects.md, "Views from above the ring"): eth-80-dev's views at ELEVATION (all.csv), each
# object's in azimuth order, four at a time, one sequence per four (an object's last views are
# left out when fewer than four remain, as viewpoint.sh leaves them), with their azimuths and
# absolute paths. `orbit eval --manifest ring.csv --queries FILE --n 4` then recognises each
# sequence against the ring's models with the pipeline `orbit serve` runs, in seconds instead of
# the minutes an end-to-end run through a server takes; `--boxes boxes.csv` cuts every frame and
# model view to its box as viewpoint.sh's cropped queries do.
#   bench/viewpoint_queries.sh [ETH80_DIR] [ELEVATION] > queries.csv
set -euo pipefail
# Absolute, with its links kept as given: `orbit eval --boxes` matches a frame to its box row by
# the path as written, so the frames must be named under the folder the boxes file is given in.
data=${1:-../shared/data/eth-80-dev}
[[ -f $data/all.csv ]] || { echo "viewpoint_queries.sh: no all.csv in $data" >&2; exit 1; }
data=$(cd "$data" && pwd -L)
elevation=${2:-24}
echo "path,object,sequence,azimuth"
awk -F, -v e="$elevation" 'NR > 1 && $4 == e { print $2, $3, $1 }' "$data/all.csv" |
  sort -k1,1 -k2,2n |
  awk -v d="$data" '
    $1 != object { flush(); object = $1; count = 0; sequence = 0 }
    { path[count] = $3; azimuth[count] = $2; ++count
      if (count == 4) { flush() } }
    function flush(   k) {
      if (count == 4) {
        for (k = 0; k < 4; ++k) printf "%s/%s,%s,%s-%d,%s\n", d, path[k], object, object, sequence, azimuth[k]
        ++sequence
      }
      count = 0
    }'
