#!/usr/bin/env bash
# Cross builds of the device library for ARM, tested under qemu-user:
#
#   scripts/cross.sh arm64|armhf
#
# Everything comes from Debian 12's packages: the cross compiler (crossbuild-essential-<arch>),
# qemu-user, and a sysroot of the target's -dev packages, unpacked from their .deb files into
# build-cross/<arch>/sysroot (no maintainer scripts run, nothing installed on the host for the
# target; a second run reuses it). Apt resolves and fetches the target's packages with its own
# state under build-cross/<arch>/apt/, so the host's package database and architectures are
# left as they are.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { echo "usage: $0 arm64|armhf" >&2; exit 2; }
[[ $# -eq 1 ]] || usage
arch=$1
case "$arch" in
  arm64) triple=aarch64-linux-gnu qemu=qemu-aarch64 ;;
  armhf) triple=arm-linux-gnueabihf qemu=qemu-arm ;;
  *) usage ;;
esac

root=$(pwd)
work="$root/build-cross/$arch"
sysroot="$work/sysroot"

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
  libflann-dev liblz4-dev
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
      grep -oE "update-alternatives$s--install$s/usr/lib/$triple/lib$w$s$w$s/$w$s[0-9]+" |
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

start=$(date +%s)
host_packages
build_sysroot
echo "cross: sysroot took $(($(date +%s) - start)) s"
