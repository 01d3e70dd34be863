#!/usr/bin/env bash
# Builds Orbit with sanitizers (GCC, RelWithDebInfo) and runs the tests under them:
#
#   scripts/sanitize.sh [asan|tsan|all]        (default all)
#
#   asan  build-asan/: AddressSanitizer (with LeakSanitizer) and UndefinedBehaviorSanitizer;
#         every ctest test (the GoogleTest suite, the Python client, the fuzz corpus replays).
#   tsan  build-tsan/: ThreadSanitizer; the tests of tests/server, tests/client, tests/cli and
#         tests/docker
#         (their test suites are read from the sources) and the Python client.
#
# The flags go in through CMAKE_CXX_FLAGS and the linker flags: CMakeLists.txt is the normal
# build's, without bench/'s measuring programs (ORBIT_BENCH=OFF), which no test runs. Every process a test starts (orbit serve, orbit import, ...) is the sanitized build's
# `orbit` (tests/CMakeLists.txt compiles its path into the tests). ASan, LSan and TSan write their
# reports to build-<name>/sanitizer-reports/<name>.<pid> instead of stderr, so that a finding in a
# server that a test only stops at the end is not lost. UBSan writes to stderr (GCC's UBSan
# runtime ignores log_path next to ASan's) and stops the process: the test fails and shows it,
# or, for a server, tests/support/server_process.cc fails the test with the server's log.
# A part fails when a test fails or a report was written; the reports are printed then.
# Suppressions (scripts/sanitizers/*.supp) are for third-party libraries only, each with its
# reason. Ends with how long each part took. With stop_on_failure set in the environment, ctest
# stops at the first failing test (CI, whose deadline may cut a part short, sets it).
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-all}
case "$what" in
  asan) parts=(asan) ;;
  tsan) parts=(tsan) ;;
  all) parts=(asan tsan) ;;
  *) echo "usage: $0 [asan|tsan|all]" >&2; exit 2 ;;
esac

./scripts/setup.sh
root=$(pwd)
supp="$root/scripts/sanitizers"

declare -A flags=(
  [asan]="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  [tsan]="-fsanitize=thread"
)

# ctest -R for tsan: the test suites of tests/server, tests/client, tests/cli and tests/docker, and the Python
# client (PythonClient.StreamsASession, which streams to a real server).
tsan_tests() {
  local suites
  suites=$(grep -hoE '^(TEST|TEST_F|TEST_P)\( *[A-Za-z0-9_]+' \
    tests/server/*_test.cc tests/client/*_test.cc tests/cli/*_test.cc tests/docker/*_test.cc |
    sed -E 's/^[A-Z_]+\( *//' | sort -u | paste -sd '|')
  echo "^(${suites}|PythonClient)\\."
}

declare -A took
failed=()

run() {
  local name=$1 build="build-$1"
  local reports="$root/$build/sanitizer-reports"
  local start
  start=$(date +%s)
  cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="${flags[$name]}" -DCMAKE_EXE_LINKER_FLAGS="${flags[$name]}" \
    -DCMAKE_SHARED_LINKER_FLAGS="${flags[$name]}" -DORBIT_BENCH=OFF >/dev/null
  local targets=()
  # tsan runs only the GoogleTest suite (with the PostgreSQL fixture its *Postgres* tests need)
  # and the Python client: no benchmarks, no fuzz replays.
  [[ $name == tsan ]] && targets=(--target orbit_tests orbit_device_tests orbit_test_postgres
    orbit_python_stubs)
  nice -n 10 cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"
  took[$name build]=$(($(date +%s) - start))

  rm -rf "$reports"
  mkdir -p "$reports"
  local select=()
  [[ $name == tsan ]] && select=(-R "$(tsan_tests)")
  start=$(date +%s)
  local status=0
  (
    cd "$build"
    export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:log_path=$reports/asan"
    export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
    # A file no other OpenCV video reader opens (the capture tests' "not a video") is also offered
    # to the gPhoto2 backend, which probes USB cameras through libgphoto2 and libusb and never
    # frees libusb's device list, from a plugin it has unloaded by exit (LSan cannot even name
    # it). Files are never read through gPhoto2: the sanitized runs leave it out.
    export OPENCV_VIDEOIO_PRIORITY_GPHOTO2=0
    # Every race of a run is reported (not only the first); the test still fails at its exit.
    # OpenCV's trackers (client/object_tracker.cc) run work on TBB's worker threads, and TBB and
    # OpenCV (uninstrumented) order it in ways TSan cannot see: every image a worker copied looked
    # like a race in cv::Mat::copyTo. ignore_noninstrumented_modules: accesses that uninstrumented
    # libraries make through TSan's interceptors (their memcpy, malloc) are not checked; every
    # access of our own code still is.
    export TSAN_OPTIONS="halt_on_error=0:second_deadlock_stack=1:ignore_noninstrumented_modules=1:suppressions=$supp/tsan.supp:log_path=$reports/tsan"
    nice -n 10 ctest --output-on-failure --parallel "$(nproc)" --timeout 900 "${select[@]}" \
      ${stop_on_failure:+--stop-on-failure}
  ) || status=$?
  took[$name tests]=$(($(date +%s) - start))

  local found
  found=$(find "$reports" -type f | sort)
  if [[ -n "$found" ]]; then
    echo "sanitize.sh: $name wrote $(echo "$found" | wc -l) report(s):" >&2
    while read -r file; do
      echo "---- $file" >&2
      cat "$file" >&2
    done <<<"$found"
    status=1
  fi
  [[ $status -eq 0 ]] || failed+=("$name")
}

for part in "${parts[@]}"; do
  run "$part"
done

echo
echo "| part | build | tests |"
echo "| --- | ---: | ---: |"
for part in "${parts[@]}"; do
  echo "| $part | $((took[$part build] / 60))m$((took[$part build] % 60))s |" \
    "$((took[$part tests] / 60))m$((took[$part tests] % 60))s |"
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "sanitize.sh: failed: ${failed[*]}" >&2
  exit 1
fi
