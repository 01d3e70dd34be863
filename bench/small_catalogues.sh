#!/usr/bin/env bash
# The accept / unknown rule on small catalogues (docs/results/recognition.md, "Small
# catalogues"). For each dataset and each catalogue SIZE, DRAWS random catalogues: SIZE objects
# enrolled, up to ten others queried as unknown, all through `orbit eval --methods product`
# (10 trials per object and n; eth-80-dev and epfl-cars cut to their boxes). Prints one Markdown
# row per dataset, size, distortion and n: known queries right and accepted (mean over the
# draws), unknown queries rejected (mean, and the worst draw).
#   bench/small_catalogues.sh [BUILD_DIR] [DATA_DIR] [SIZES] [DRAWS] [DISTORTIONS] [NS] [DATASETS]
# Defaults: build, ../shared/data, 2,5,10,20, 4, df, 1,2,4, coil,eth,epfl. A size that leaves
# fewer than two objects to play unknown ones is skipped (epfl-cars holds 20 cars).
set -euo pipefail
build=${1:-build}
data=$(realpath "${2:-../shared/data}")
IFS=, read -r -a sizes <<<"${3:-2,5,10,20}"
draws=${4:-4}
distortions=${5:-df}
ns=${6:-1,2,4}
IFS=, read -r -a datasets <<<"${7:-coil,eth,epfl}"
orbit="$build/orbit"
errors=$(mktemp)
trap 'rm -f "$errors"' EXIT

# The eval arguments and object count of a dataset.
dataset_arguments() {
  case $1 in
    coil) echo "--data $data/coil-100" ;;
    eth) echo "--manifest $data/eth-80-dev/ring.csv --boxes $data/eth-80-dev/boxes.csv" ;;
    epfl) echo "--manifest $data/epfl-cars/manifest.csv --boxes $data/epfl-cars/boxes.csv --box-margin 0" ;;
    *) echo "unknown dataset $1 (coil, eth, epfl)" >&2; exit 2 ;;
  esac
}
dataset_objects() {
  case $1 in coil) echo 100 ;; eth) echo 40 ;; epfl) echo 20 ;; esac
}

echo "| dataset | objects | distortion | n | known right and accepted | unknown rejected | worst draw |"
echo "|---|---:|---|---:|---:|---:|---:|"
for dataset in "${datasets[@]}"; do
  read -r -a arguments <<<"$(dataset_arguments "$dataset")"
  total=$(dataset_objects "$dataset")
  for size in "${sizes[@]}"; do
    ((size + 2 <= total)) || continue
    rows=""
    for ((draw = 0; draw < draws; ++draw)); do
      # A shuffle of 1..total seeded by size and draw: the first SIZE are enrolled, the next
      # (up to ten) unknown.
      order=$(awk -v n="$total" -v seed=$((1000 * size + draw + 1)) 'BEGIN {
        srand(seed); for (i = 1; i <= n; ++i) a[i] = i
        for (i = n; i > 1; --i) { j = int(rand() * i) + 1; t = a[i]; a[i] = a[j]; a[j] = t }
        for (i = 1; i <= n; ++i) print a[i] }')
      known=$(head -n "$size" <<<"$order" | sort -n | paste -sd,)
      unknown=$(tail -n +"$((size + 1))" <<<"$order" | head -n 10 | sort -n | paste -sd,)
      # The recognition table's rows: | product | variant | DIST | n | right+accepted | rejected
      # | accepted wrong | unknown rejected | ...
      rows+=$("$orbit" eval "${arguments[@]}" --methods product --no-progress \
        --distortions "$distortions" --n "$ns" --trials 10 --seed $((draw + 1)) \
        --objects "$known" --unknown-objects "$unknown" 2>"$errors" |
        awk -F'|' '$2 ~ /^ product $/ && $6 ~ /[0-9]/ { print $4 "|" $5 "|" $6 "|" $9 }')
      [[ -n $rows ]] || { cat "$errors" >&2; exit 1; }
      rows+=$'\n'
    done
    awk -F'|' -v dataset="$dataset" -v size="$size" 'NF == 4 {
        key = $1 "|" $2; if (!(key in count)) order[++keys] = key
        count[key]++; known[key] += $3; unknown[key] += $4
        if (!(key in worst) || $4 < worst[key]) worst[key] = $4 }
      END { for (k = 1; k <= keys; ++k) { key = order[k]; split(key, part, "|")
        gsub(/ /, "", part[1]); gsub(/ /, "", part[2])
        printf "| %s | %d | %s | %s | %.1f | %.1f | %.1f |\n", dataset, size, part[1], part[2],
          known[key] / count[key], unknown[key] / count[key], worst[key] } }' <<<"$rows"
  done
done
