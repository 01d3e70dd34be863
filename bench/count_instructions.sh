#!/usr/bin/env bash
# Instructions a cross-built device executes per piece of per-frame work, counted under
# qemu-user (docs/results/device.md, "Instruction counts under emulation"):
#
#   bench/count_instructions.sh arm64|armhf [WORK...]
#
# Needs scripts/cross.sh's build of that architecture (build-cross/<arch>/orbit_device_work and
# its sysroot) and the shared data (../shared/data, or $ORBIT_DATA). WORK: what
# bench/device_work_main.cc does, by default every variant's whole frame, the tracker, the
# frame quality and the product's device frame.
#
# How: qemu logs every block of instructions it translates (-d in_asm) and every execution of a
# block (-d exec, with the blocks' chaining off so that none runs unlogged: nochain). The
# instructions executed are the sum over executions of the block's size. Each work runs with
# TIMES 1 and 2: the difference is one more time's cost, without the program's start, the
# work's set-up and what its first time alone pays. Slow: the emulator logs every block (about
# a million a second), and each run starts the program (loading its libraries: some 540 million
# instructions) and sets its work up again (a walk's work renders the walk first: ten minutes
# or more a run on the 2-core development machine).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { echo "usage: $0 arm64|armhf [WORK...]" >&2; exit 2; }
[[ $# -ge 1 ]] || usage
case "$1" in
  arm64) qemu="qemu-aarch64" ;;
  armhf) qemu="qemu-arm" ;;
  *) usage ;;
esac
build="$(pwd)/build-cross/$1"
shift
works=("$@")
[[ ${#works[@]} -gt 0 ]] || works=(cedd-lire cedd-full cedd-robust cedd-hsv-hog track quality
  device-frame:cedd-hsv-hog)
program="$build/orbit_device_work"
data=$(realpath "${ORBIT_DATA:-../shared/data}")
[[ -x "$program" ]] || { echo "count: no $program: run scripts/cross.sh first" >&2; exit 1; }

# Instructions executed by one run of the program: WORK TIMES.
count() {
  "$qemu" -L "$build/sysroot" -d in_asm,exec,nochain -D /dev/fd/3 "$program" "$1" "$2" "$data" \
    3>&1 >/dev/null | awk '
      /^IN:/ { block = 1; pc = ""; next }
      block && /^0x[0-9a-f]+:/ {
        if (pc == "") { pc = substr($1, 3, length($1) - 3); sub(/^0+/, "", pc); size[pc] = 0 }
        size[pc]++; next
      }
      block && /^$/ { block = 0; next }
      /^Trace / { split($4, f, "/"); p = f[2]; sub(/^0+/, "", p); total += size[p] }
      END { printf "%d\n", total }'
}

"$qemu" --version | head -1
printf '%-26s %15s\n' work "per time"
printf '%-26s %15d  (the program start alone, once)\n' none "$(count none 0)"
for work in "${works[@]}"; do
  once=$(count "$work" 1)
  twice=$(count "$work" 2)
  printf "%-26s %15d\n" "$work" $((twice - once))
done
