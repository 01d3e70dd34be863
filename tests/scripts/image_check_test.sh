#!/usr/bin/env bash
# scripts/image.sh --check, the images' check that builds no image: it passes on docker/ as it
# is, and refuses, naming the package and what to change, copies of docker/ whose server image
# would lack a library orbit-server links, or would install one only the device commands use,
# or whose balancer image names a package Debian does not have.
#   tests/scripts/image_check_test.sh SOURCE_DIR BUILD_DIR
# BUILD_DIR: a build holding orbit-server.
set -euo pipefail
source_dir=$(realpath "$1")
build_dir=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

check() { DOCKER_DIR="$work/docker" "$source_dir/scripts/image.sh" --check "$build_dir"; }
fresh_copy() {
  rm -rf "$work/docker"
  cp -r "$source_dir/docker" "$work/docker"
}
expect_refusal() {  # expect_refusal WHAT MESSAGE: --check fails on the copy, saying MESSAGE
  local out
  if out=$(check 2>&1); then
    echo "FAIL: --check passed docker/ $1" >&2
    exit 1
  fi
  grep -qF -- "$2" <<<"$out" || {
    echo "FAIL: --check refused docker/ $1 without saying: $2" >&2
    echo "$out" >&2
    exit 1
  }
}

fresh_copy
check

fresh_copy
sed -i 's/ libprometheus-cpp-pull1.0//' "$work/docker/Dockerfile"
expect_refusal "without the metrics endpoint's library" \
  "does not install it: add libprometheus-cpp-pull1.0 to its apt-get install"

fresh_copy
sed -i 's/ libopencv-imgcodecs406/ libopencv-imgcodecs406 libopencv-videoio406/' \
  "$work/docker/Dockerfile"
expect_refusal "with OpenCV's video I/O" \
  "installs libopencv-videoio406, which only the device commands need"

fresh_copy
sed -i 's/ haproxy / haproxy-balancer /' "$work/docker/balancer.Dockerfile"
expect_refusal "with a misspelt package" \
  "installs haproxy-balancer, which Debian 12's archive does not have"

echo "PASS"
