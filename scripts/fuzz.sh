#!/usr/bin/env bash
# Fuzzes every target of fuzz/ (or the TARGETs named) for SECONDS each (default 600), then prints
# one Markdown table row per target: runs, executions per second, the corpus it ends with
# (inputs/size, as libFuzzer counts them), and the crashes, leaks, timeouts and out-of-memory
# inputs found (distinct inputs, not distinct bugs).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]        e.g. scripts/fuzz.sh 60 cedd manifest
#
# Builds build-fuzz/ first (clang, -DORBIT_FUZZ=ON: libFuzzer with ASan and UBSan). Each target
# starts from its seeds (fuzz/corpus/TARGET, never written to) and from what earlier runs found in
# build-fuzz/fuzz-runs/TARGET/corpus, where new inputs go. libFuzzer stops at a finding (saving it
# in build-fuzz/fuzz-runs/TARGET/artifacts/ as crash-*, leak-*, timeout-* or oom-*; reproduce it
# with build-fuzz/fuzz/TARGET_fuzzer FILE), so it is started again until the time is up; the log
# of every start is in .../log. Runs and executions per second add up every start.
# ORBIT_FUZZ_JOBS=2 runs two targets at a time (default 1); niced, as long runs should be.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-600}
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "usage: $0 [SECONDS] [TARGET...]" >&2; exit 2; }
shift || true
jobs=${ORBIT_FUZZ_JOBS:-1}
build=build-fuzz

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DORBIT_FUZZ=ON "${launcher[@]}" >/dev/null
nice -n 10 cmake --build "$build" --parallel "$(nproc)"

if [[ $# -gt 0 ]]; then
  targets=("$@")
else
  targets=()
  for source in fuzz/*_fuzzer.cc; do
    name=$(basename "$source" _fuzzer.cc)
    targets+=("$name")
  done
fi

mapfile -t flags < <(grep '^-' fuzz/libfuzzer_flags)

run() {
  local name=$1 dir="$build/fuzz-runs/$1"
  local binary="$build/fuzz/${name}_fuzzer"
  [[ -x "$binary" ]] || { echo "no fuzz target $name ($binary)" >&2; return 1; }
  mkdir -p "$dir/corpus" "$dir/artifacts"
  : >"$dir/log"
  local dictionary=()
  [[ -f "fuzz/$name.dict" ]] && dictionary=("-dict=fuzz/$name.dict")
  echo "fuzz.sh: $name for ${seconds}s (log: $dir/log)" >&2
  local start left
  start=$(date +%s)
  while left=$((start + seconds - $(date +%s))) && [[ $left -gt 0 ]]; do
    nice -n 15 "$binary" "${flags[@]}" "${dictionary[@]}" -max_total_time="$left" \
      -print_final_stats=1 -artifact_prefix="$dir/artifacts/" "$dir/corpus" "fuzz/corpus/$name" \
      >"$dir/last-log" 2>&1 || true
    cat "$dir/last-log" >>"$dir/log"
    # A seed that fails stops libFuzzer before it starts fuzzing: starting again would not help.
    grep -q INITED "$dir/last-log" || break
  done
  echo $(($(date +%s) - start)) >"$dir/seconds"
}

running=0
for name in "${targets[@]}"; do
  run "$name" &
  running=$((running + 1))
  if [[ $running -ge $jobs ]]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

count() { find "$1" -maxdepth 1 -type f -name "$2-*" | wc -l; }

echo
echo "| target | runs | execs/s | corpus (inputs/size) | crashes | leaks | timeouts | ooms |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for name in "${targets[@]}"; do
  dir="$build/fuzz-runs/$name"
  runs=$(awk '/^stat::number_of_executed_units:/ { n += $2 } END { print n + 0 }' "$dir/log")
  elapsed=$(cat "$dir/seconds" 2>/dev/null || echo 0)
  # libFuzzer's own account of the corpus it ended with (seeds and new inputs): "corp: 219/148Kb".
  corpus=$(grep -oE 'corp: [0-9]+/[0-9]+[A-Za-z]*' "$dir/log" | tail -n 1 | cut -d' ' -f2)
  echo "| $name | $runs | $((runs / (elapsed > 0 ? elapsed : 1))) | ${corpus:-?} |" \
    "$(count "$dir/artifacts" crash) | $(count "$dir/artifacts" leak) |" \
    "$(count "$dir/artifacts" timeout) | $(count "$dir/artifacts" oom) |"
done
