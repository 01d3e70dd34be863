#!/usr/bin/env bash
# Installs the Debian 12 packages Orbit needs to build, test and run. Idempotent, non-interactive,
# and quick when everything is already there (no apt-get update then). Runs as root, or through
# sudo when it is available.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git clang libclang-rt-14-dev
  clang-format  # the layout check of scripts/format.sh
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libopencv-video-dev libopencv-videoio-dev libopencv-contrib-dev  # captures, object tracking
  libcli11-dev nlohmann-json3-dev libsqlite3-dev libpq-dev
  libabsl-dev  # thread-safety annotations, header only (core/base/mutex.h)
  libgtest-dev libgmock-dev libbenchmark-dev
  libflann-dev liblz4-dev libeigen3-dev zlib1g-dev prometheus-cpp-dev
  libhnswlib-dev  # the view index's graphs of object summaries (core/index/view_index.h)
  libfaiss-dev  # faiss's HNSW and IVF indexes, measured against hnswlib (bench/candidate_search_bench.cc)
  libgoogle-perftools-dev  # tcmalloc, build/orbit's allocator (cmake/OrbitDeps.cmake)
  libgrpc++-dev libprotobuf-dev protobuf-compiler protobuf-compiler-grpc openssl
  libssl-dev  # SHA-256 of the server's tokens (server/token_file.h)
  python3-grpcio python3-protobuf
  postgresql-15  # the tests' PostgreSQL server (tests/support/postgres_test_cluster.h)
  haproxy  # the gRPC balancer of docker/haproxy.cfg, run by tests/docker/replicas_test.cc
  jq  # bench/served_frame_cost.sh reads orbit loadtest's JSON
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: run as root (or install sudo) to install: ${missing[*]}" >&2; exit 1; }
  as_root=(sudo)
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
