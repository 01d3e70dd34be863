#!/usr/bin/env bash
# Cross builds of the device library for ARM, tested under qemu-user:
#
#   scripts/cross.sh arm64|armhf [STEP...]
#
# runs these steps (or only the STEPs named, on what earlier runs built: device_bit_identity
# device_example checks a built tree in a few minutes):
# 1. The host's packages (scripts/setup.sh), the cross compiler (crossbuild-essential-<arch>)
#    and qemu-user, all from Debian 12.
# 2. A sysroot of the target's -dev packages and their dependencies, unpacked from their .deb
#    files into build-cross/<arch>/sysroot: no maintainer script runs and nothing is installed
#    on the host for the target. Apt resolves and fetches them with its own state under
#    build-cross/<arch>/apt/, so the host's package database and architectures stay as they are.
#    A second run reuses the sysroot.
# 3. The host's `orbit` (build/orbit): the tests' server, as an edge server is to a device; and
#    its orbit_describe_images.
# 4. The device build (-DORBIT_DEVICE_ONLY=ON: the device libraries and their tests) into
#    build-cross/<arch> with cmake/toolchains/<triple>.cmake, and every test under qemu (ctest),
#    the descriptors' bit-exactness included (docs/design.md#exactness, #hot-loops); then every
#    variant's descriptor of the conformance set and COIL-100, compared byte for byte with this
#    machine's.
# 5. The installed package: `cmake --install` into build-cross/<arch>/prefix, examples/
#    capture_client built against it with the toolchain, run under qemu: its usage, then an
#    enrollment of two objects and a recognition against the host's server on loopback.
# Every step runs even when one fails; the script ends with each step's result and time, and
# fails if one did. Not part of CI (.ci/run): it takes longer than CI has left.
# The steps are functions called by name ("$step" below), which shellcheck cannot follow.
# shellcheck disable=SC2317
set -euo pipefail
cd "$(dirname "$0")/.."

steps=(host_packages build_sysroot host_build device_build device_tests device_bit_identity
  device_example)
usage() { echo "usage: $0 arm64|armhf [STEP...]   (steps: ${steps[*]})" >&2; exit 2; }
[[ $# -ge 1 ]] || usage
# --help: the comment at the top of this file, what each step does.
if [[ $1 == -h || $1 == --help ]]; then
  sed -n '2,/^# shellcheck/p' "$0" | grep -v '^# shellcheck\|^# The steps are functions' | sed 's/^# \{0,1\}//'
  exit 0
fi
arch=$1
shift
if [[ $# -gt 0 ]]; then
  for step in "$@"; do
    [[ " ${steps[*]} " == *" $step "* ]] || usage
  done
  steps=("$@")
fi
case "$arch" in
  arm64) triple=aarch64-linux-gnu qemu=qemu-aarch64 ;;
  armhf) triple=arm-linux-gnueabihf qemu=qemu-arm ;;
  *) usage ;;
esac

root=$(pwd)
work="$root/build-cross/$arch"  # the device build; sysroot/, apt/, prefix/, example/ inside
sysroot="$work/sysroot"
toolchain="$root/cmake/toolchains/$triple.cmake"
data=${ORBIT_DATA:-$root/../shared/data}

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "cross: run as root (or install sudo)" >&2; exit 1; }
  as_root=(sudo)
fi

# The host's packages: the build tools (scripts/setup.sh), the cross compiler and qemu-user.
host_packages() {
  ./scripts/setup.sh
  local missing=() p status
  for p in "crossbuild-essential-$arch" qemu-user; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [[ "$status" == "install ok installed" ]] || missing+=("$p")
  done
  [[ ${#missing[@]} -eq 0 ]] && return
  echo "cross: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${as_root[@]}" apt-get update -qq
  "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# The target's packages in the sysroot: what the device library, its tests and the example
# compile and link against, and the C and C++ runtimes (the cross compiler looks for them in the
# sysroot too). Their dependencies come along, and run the target's programs under qemu.
sysroot_packages=(
  libc6-dev libstdc++-12-dev
  libgrpc++-dev libprotobuf-dev libabsl-dev zlib1g-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libopencv-video-dev libopencv-videoio-dev libopencv-contrib-dev
  libgtest-dev libgmock-dev
)

# apt on the target's architecture, with its own lists, cache and an empty package database:
# the dependency closure of sysroot_packages as if on an empty target machine.
target_apt() {
  apt-get -o "APT::Architecture=$arch" -o "APT::Architectures=$arch" \
    -o "Dir::State=$work/apt" -o "Dir::State::status=$work/apt/status" \
    -o "Dir::Cache=$work/apt/cache" -o Acquire::Languages=none \
    -o APT::Sandbox::User=root -o Debug::NoLocking=true "$@"
}

build_sysroot() {
  local stamp="$sysroot/.packages"
  if [[ -f "$stamp" && "$(cat "$stamp")" == "${sysroot_packages[*]}" ]]; then
    echo "cross: reusing $sysroot"
    return
  fi
  echo "cross: building the $arch sysroot in $sysroot"
  mkdir -p "$work/apt/lists/partial" "$work/apt/cache/archives/partial"
  touch "$work/apt/status"
  # An index that fails to download (a mirror in the middle of a sync) leaves its packages out;
  # the packages needed must still resolve from the others, or the download below stops.
  target_apt update -qq || echo "cross: apt-get update reported errors; going on with the indexes it has" >&2
  target_apt install -y -qq --download-only --no-install-recommends "${sysroot_packages[@]}"

  rm -rf "$sysroot.new"
  mkdir -p "$sysroot.new"
  find "$work/apt/cache/archives" -maxdepth 1 -name '*.deb' -print0 |
    xargs -0 -P "$(nproc)" -I{} dpkg-deb -x {} "$sysroot.new"
  # Absolute symlinks (/usr/lib/<triple>/libz.so -> /lib/<triple>/libz.so.1) point at the host's
  # files; made relative, they point inside the sysroot for the linker and for qemu.
  local link target
  while IFS= read -r -d '' link; do
    target=$(readlink "$link")
    [[ "$target" == /* ]] || continue
    ln -sfn "$(realpath -s -m --relative-to="$(dirname "$link")" "$sysroot.new$target")" "$link"
  done < <(find "$sysroot.new" -type l -print0)
  # Shared libraries that Debian selects with update-alternatives in a maintainer script
  # (libblas.so.3, liblapack.so.3, which OpenCV links): the link the script would make, from each
  # package's `update-alternatives --install LINK NAME PATH PRIORITY`, the highest priority last.
  local deb s='[[:space:]]+' w='[^[:space:]]+'
  for deb in "$work/apt/cache/archives/"*.deb; do
    dpkg-deb --ctrl-tarfile "$deb" | { tar -xO ./postinst 2>/dev/null || true; } |
      sed -e ':a' -e '/\\$/N; s/\\\n//; ta' |
      grep -oE "update-alternatives$s--install$s/usr/lib/$triple/lib$w$s$w$s/$w${s}[0-9]+" |
      awk '{ print $6, $3, $5 }' || true
  done | sort -n | while read -r _ link target; do
    [[ -e "$sysroot.new$target" ]] || continue
    ln -sfn "$(realpath -s -m --relative-to="$(dirname "$sysroot.new$link")" "$sysroot.new$target")" \
      "$sysroot.new$link"
  done
  # gRPC's CMake package names its code generators as programs of the sysroot's /usr/bin and
  # refuses to load when they are missing. The build runs the host's (proto/CMakeLists.txt), so
  # the sysroot's names point at them.
  local plugin
  for plugin in /usr/bin/grpc_*_plugin; do
    ln -sfn "$plugin" "$sysroot.new$plugin"
  done
  printf '%s' "${sysroot_packages[*]}" >"$sysroot.new/.packages"
  rm -rf "$sysroot"
  mv "$sysroot.new" "$sysroot"
  rm -f "$work/apt/cache/archives/"*.deb
  echo "cross: sysroot ready ($(du -sh "$sysroot" | cut -f1))"
}

# From build/, configured as scripts/build.sh does: `orbit`, the tests' server, and
# orbit_describe_images, this machine's descriptors for device_bit_identity.
host_build() {
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="${ORBIT_BUILD_TYPE:-Release}" >/dev/null
  cmake --build build --parallel "$(nproc)" --target orbit orbit_describe_images
}

device_build() {
  cmake -S . -B "$work" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DCMAKE_BUILD_TYPE=Release \
    -DORBIT_DEVICE_ONLY=ON -DORBIT_TEST_SERVER="$root/build/orbit" >/dev/null
  cmake --build "$work" --parallel "$(nproc)"
}

# Under emulation the device's side runs several times slower than on a device, so on a loaded
# machine a call can outlast its deadline: a test that fails is run again alone, and fails the
# step only when it fails again.
device_tests() {
  cd "$work"
  if ! ctest --output-on-failure --parallel "$(nproc)" --timeout 1800; then
    echo "cross: running the failed tests again, one at a time"
    ctest --rerun-failed --output-on-failure --timeout 1800
  fi
}

# Every variant's descriptor of every image of the CEDD conformance set and of COIL-100, by the
# target under qemu and by this machine (its fastest hot loops): the same lines, byte for byte
# (docs/design.md#exactness).
device_bit_identity() {
  local folders=("$data/cedd-conformance" "$data/coil-100")
  build/orbit_describe_images "${folders[@]}" >"$work/describe-host.txt"
  "$qemu" -L "$sysroot" "$work/orbit_describe_images" "${folders[@]}" >"$work/describe-$arch.txt"
  if ! cmp "$work/describe-host.txt" "$work/describe-$arch.txt"; then
    echo "cross: $arch describes some images differently from this machine:" >&2
    diff "$work/describe-host.txt" "$work/describe-$arch.txt" | head -20 >&2
    return 1
  fi
  echo "cross: $(wc -l <"$work/describe-host.txt") descriptors, identical on $arch and here"
}

# The example, built against the installed package as a device application would be, and run
# under qemu against the host's server.
device_example() {
  local prefix="$work/prefix" example="$work/example" status=0
  rm -rf "$prefix"
  cmake --install "$work" --prefix "$prefix" >/dev/null
  # The prefix is the target's: a root path beside the sysroot for find_package(OrbitClient).
  cmake -S examples/capture_client -B "$example/build" -G Ninja \
    -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_ROOT_PATH="$prefix" >/dev/null
  cmake --build "$example/build"
  local client=("$qemu" -L "$sysroot" "$example/build/orbit_capture_client")

  "${client[@]}" 2>"$example/usage.txt" || status=$?
  if [[ $status -ne 2 ]] || ! grep -q '^usage: ' "$example/usage.txt"; then
    echo "cross: the example without arguments exited $status, not 2 with its usage:" >&2
    cat "$example/usage.txt" >&2
    return 1
  fi

  # Two objects enrolled from walks round them, then a walk round the first from other azimuths.
  local box=105,94,110,110  # the first box `orbit walk` prints for these walks
  build/orbit walk --coil "$data/coil-100" --object 3 --video "$example/obj3.avi" \
    --orientation "$example/obj3.csv" >/dev/null
  build/orbit walk --coil "$data/coil-100" --object 10 --video "$example/obj10.avi" \
    --orientation "$example/obj10.csv" >/dev/null
  build/orbit walk --coil "$data/coil-100" --object 3 --video "$example/query.avi" \
    --orientation "$example/query.csv" --frames 12 --start 7 --turn 60 --seed 2 >/dev/null
  # shellcheck source=bench/serve_in_background.sh
  source bench/serve_in_background.sh
  rm -f "$example/models.db"
  serve_in_background build/orbit "$example/serve.log" --db "$example/models.db"
  trap 'kill "$server_pid" 2>/dev/null || true' EXIT
  "${client[@]}" "$address" "$example/obj3.avi" "$example/obj3.csv" "$box" enroll obj3
  "${client[@]}" "$address" "$example/obj10.avi" "$example/obj10.csv" "$box" enroll obj10
  "${client[@]}" "$address" "$example/query.avi" "$example/query.csv" "$box" recognize |
    tee "$example/recognize.txt"
  kill "$server_pid"
  trap - EXIT
  if ! grep -q '^frame 11: obj3 ' "$example/recognize.txt" ||
    ! grep -q '^12 frames sent, 0 lost$' "$example/recognize.txt"; then
    echo "cross: the example's walk round obj3 was not answered obj3 on its last frame" >&2
    return 1
  fi
}

# Every step runs, and the run fails at the end if one failed: a failing test does not hide
# what the later steps would have found.
# Each step runs in a subshell of its own with errexit on (in an `if`, bash would ignore it).
declare -A took result
failed=0
for step in "${steps[@]}"; do
  echo "cross: $step"
  start=$(date +%s)
  set +e
  (
    set -e
    "$step"
  )
  status=$?
  set -e
  if [[ $status -eq 0 ]]; then result[$step]=ok; else result[$step]=FAILED; failed=1; fi
  took[$step]=$(($(date +%s) - start))
done

echo "cross: $arch"
total=0
for step in "${steps[@]}"; do
  printf '  %-20s %-6s %5d s\n' "$step" "${result[$step]}" "${took[$step]}"
  total=$((total + took[$step]))
done
printf '  %-20s %-6s %5d s\n' total "" "$total"
exit "$failed"
