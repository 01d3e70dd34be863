#!/usr/bin/env bash
# Builds every image of docker/ with buildah and smoke-tests it, on a machine with no Docker
# engine and no registry: only Debian's package archive.
#
#   scripts/image.sh [BUILD_DIR]            # build and smoke-test the images (as root)
#   scripts/image.sh --check [BUILD_DIR]    # no image: check the Dockerfiles against Debian
#
# BUILD_DIR (default build/) holds the host's tools: `orbit`, which enrolls and recognises
# through the running server image, and for --check `orbit-server`.
#
# Full run: installs buildah and debootstrap when missing; when the image store holds no
# debian:12 and debian:12-slim, makes them (debootstrap --variant=minbase bookworm, the slim one
# without documentation as Debian's slim images are); builds docker/Dockerfile as orbit:latest
# and docker/balancer.Dockerfile as orbit-balancer:latest from the tree as git sees it (tracked
# and new files, nothing ignored, so no build directory); then runs them (buildah run, chroot
# isolation, the host's network). The server image, its SQLite store on a host folder mounted
# as its volume, answers `orbit-server info`; three COIL-100 objects are enrolled through it with
# the host's `orbit enroll`, and `orbit recognize` of views it was not enrolled from names the
# right object; a new container on the same folder still holds and recognises them; the
# balancer image, on docker/haproxy.cfg with that server as replica 1 and the other two absent,
# keeps the server up through its grpc.health.v1 checks and passes a call to it. Prints each
# image's size and fails when the server image is over 300 MB.
#
# --check: every package the Dockerfiles install exists in Debian's archive (the host's apt
# lists), the server image's runtime stage installs the package of every library orbit-server
# links, and none of the packages only the device commands need (OpenCV video, video I/O,
# contrib). Fails naming the package and what to change.
#
# Environment: ORBIT_DATA (default ../shared/data), SCRATCH (default /var/tmp/orbit-image: the
# Debian base, the build context, the volume), MIRROR (default: the host's Debian archive),
# DOCKER_DIR (default docker/: the Dockerfiles --check reads).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
check=false
case "${1:-}" in
  -h | --help) usage; exit 0 ;;
  --check) check=true; shift ;;
  -*) echo "image.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
esac
build=${1:-build}
docker_dir=${DOCKER_DIR:-docker}
data=${ORBIT_DATA:-../shared/data}
scratch=${SCRATCH:-/var/tmp/orbit-image}
server_image=orbit:latest
balancer_image=orbit-balancer:latest
max_server_mb=300
# The Debian packages whose libraries only the device commands load (captures, tracking).
device_packages=(libopencv-video406 libopencv-videoio406 libopencv-contrib406)

fail() { echo "image.sh: $*" >&2; exit 1; }

# The packages the `apt-get install` of a Dockerfile's last stage names (the runtime stage), or
# of every stage with --all.
installed_packages() {  # installed_packages DOCKERFILE [--all]
  local file=$1 scope=${2:-last}
  # One instruction per line, continuations joined; the last FROM starts the runtime stage.
  sed -e ':a' -e '/\\$/{N; s/\\\n//; ba}' "$file" |
    awk -v scope="$scope" '/^FROM /{ if (scope == "last") text = ""; next } { text = text "\n" $0 }
      END { print text }' |
    grep -o 'apt-get install[^&;]*' | tr ' ' '\n' |
    grep -v -e '^$' -e '^-' -e '^apt-get$' -e '^install$' | sort -u
}

check_dockerfiles() {
  local server_binary=$build/orbit-server
  [[ -x $server_binary ]] ||
    fail "no $server_binary: build it first (cmake --build $build --target orbit-server)"
  apt-cache show --no-all-versions libc6 >/dev/null 2>&1 ||
    fail "apt knows no packages here: run apt-get update"
  local file package named known
  for file in "$docker_dir"/Dockerfile "$docker_dir"/balancer.Dockerfile; do
    named=$(installed_packages "$file" --all)
    # shellcheck disable=SC2086  # one word per package
    known=$( (apt-cache show --no-all-versions $named 2>/dev/null || true) |
      sed -n 's/^Package: //p')
    for package in $named; do
      grep -qx "$package" <<<"$known" ||
        fail "$file installs $package, which Debian 12's archive does not have"
    done
  done

  # What the runtime stage's apt-get installs: the packages it names and their dependencies.
  local runtime
  runtime=$(installed_packages "$docker_dir/Dockerfile")
  [[ -n $runtime ]] || fail "$docker_dir/Dockerfile's runtime stage installs no package"
  local closure
  # shellcheck disable=SC2086  # one word per package
  closure=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts \
    --no-breaks --no-replaces --no-enhances $runtime | grep -v '^ ' | sort -u)
  for package in "${device_packages[@]}"; do
    if grep -qx "$package" <<<"$closure"; then
      fail "$docker_dir/Dockerfile's runtime stage installs $package, which only the device" \
        "commands need: orbit-server must not link it (cli/CMakeLists.txt)"
    fi
  done

  # The package of each library the binary links directly: "PACKAGE:ARCH: PATH" lines of dpkg.
  local sonames owners soname owner
  # A sanitizer build's runtime (scripts/sanitize.sh) never goes into an image: not checked.
  sonames=$(readelf -d "$server_binary" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' |
    grep -v -E '^lib(a|ub|t|l)san\.so')
  # shellcheck disable=SC2046  # one pattern per library
  owners=$(dpkg -S $(sed "s|^|*/$(gcc -dumpmachine)/|" <<<"$sonames") 2>/dev/null || true)
  for soname in $sonames; do
    owner=$(grep -F "/$soname" <<<"$owners" | grep -v -- '-dev:' | head -1 | cut -d: -f1)
    [[ -n $owner ]] || fail "no Debian package on this machine holds $soname, which" \
      "$server_binary links"
    grep -qx "$owner" <<<"$closure" ||
      fail "$server_binary links $soname, but $docker_dir/Dockerfile's runtime stage does not" \
        "install it: add $owner to its apt-get install"
  done
  echo "image.sh --check: the Dockerfiles' packages exist; the server image's runtime stage" \
    "installs every library $server_binary links, and no device-only one"
}

if $check; then
  check_dockerfiles
  exit 0
fi

# ---- the full run --------------------------------------------------------------------------
[[ $(id -u) -eq 0 ]] || fail "run as root (buildah's chroot isolation and debootstrap need it)"
orbit=$build/orbit
[[ -x $orbit ]] || fail "no $orbit: build it first (cmake --build $build --target orbit)"
[[ -d $data/coil-100 ]] || fail "no COIL-100 in $data: set ORBIT_DATA to the shared data"
started=$SECONDS

missing=()
for tool in buildah debootstrap; do command -v "$tool" >/dev/null || missing+=("$tool"); done
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "image.sh: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
mkdir -p "$scratch"
scratch=$(cd "$scratch" && pwd)

containers=()
pids=()
cleanup() {
  local pid container
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  for container in "${containers[@]}"; do buildah rm "$container" >/dev/null 2>&1 || true; done
}
trap cleanup EXIT

has_image() { buildah inspect --type image "$1" >/dev/null 2>&1; }

# Debian 12 made here, since no registry is reachable: debian:12 is minbase with its package
# lists and downloads removed; debian:12-slim is that without documentation, man pages and
# translations, and with the dpkg rule that keeps them out of later installs, as Debian's slim
# images are made.
make_debian_base() {
  local mirror=${MIRROR:-}
  if [[ -z $mirror ]]; then
    mirror=$(sed -n 's/^URIs: *\(\S*debian\)$/\1/p' /etc/apt/sources.list.d/*.sources \
      2>/dev/null | head -1)
    mirror=${mirror:-http://deb.debian.org/debian}
  fi
  local root=$scratch/debian-12
  rm -rf "$root"
  echo "image.sh: making debian:12 with debootstrap from $mirror"
  debootstrap --variant=minbase bookworm "$root" "$mirror" >"$scratch/debootstrap.log" 2>&1 ||
    fail "debootstrap failed, see $scratch/debootstrap.log"
  rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
  import_root "$root" debian:12
  cat >"$root/etc/dpkg/dpkg.cfg.d/slim" <<'EOF'
path-exclude /usr/share/doc/*
path-include /usr/share/doc/*/copyright
path-exclude /usr/share/man/*
path-exclude /usr/share/groff/*
path-exclude /usr/share/info/*
path-exclude /usr/share/lintian/*
path-exclude /usr/share/linda/*
path-exclude /usr/share/locale/*
path-include /usr/share/locale/locale.alias
EOF
  find "$root/usr/share/doc" -mindepth 1 -not -name copyright -not -type d -delete
  find "$root/usr/share/locale" -mindepth 1 -maxdepth 1 -not -name locale.alias \
    -exec rm -rf {} +
  rm -rf "$root"/usr/share/{man,groff,info,lintian,linda}/*
  import_root "$root" debian:12-slim
  rm -rf "$root"
}

import_root() {  # import_root FOLDER NAME: the folder as the one layer of image NAME
  local container mount
  container=$(buildah from scratch)
  mount=$(buildah mount "$container")
  cp -a "$1"/. "$mount"/
  buildah umount "$container" >/dev/null
  buildah config --cmd /bin/bash \
    --env PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin "$container"
  buildah commit --quiet --rm "$container" "$2" >/dev/null
}

if ! has_image debian:12 || ! has_image debian:12-slim; then
  make_debian_base
fi

# The build context: the files git sees, as they are in the working tree.
context=$scratch/context
rm -rf "$context"
mkdir -p "$context"
git ls-files -z --cached --others --exclude-standard |
  while IFS= read -r -d '' file; do [[ -e $file ]] && printf '%s\0' "$file"; done |
  tar --null -T - -cf - | tar -xf - -C "$context"

bud() {  # bud DOCKERFILE TAG CONTEXT
  local stage_started=$SECONDS
  echo "image.sh: building $2 from $1"
  local log
  log=$scratch/$(basename "$1").log
  buildah bud --isolation chroot --network host --format docker --pull=never --layers --force-rm \
    -f "$context/$1" -t "$2" "$3" >"$log" 2>&1 || {
    tail -40 "$log" >&2
    fail "building $2 failed (log: $log)"
  }
  echo "image.sh: built $2 in $((SECONDS - stage_started)) s"
}
bud docker/Dockerfile "$server_image" "$context"
bud docker/balancer.Dockerfile "$balancer_image" "$context/docker"

# ---- smoke test: the server on a host folder as its volume ----------------------------------
volume=$scratch/volume
rm -rf "$volume"
mkdir -p "$volume"

# run_in NAME LOG ARGS...: a new container of image NAME running ARGS in the background, the
# host folder $volume as /var/lib/orbit; sets `pid` (buildah run's) and `container`.
run_in() {
  local image=$1 log=$2
  shift 2
  container=$(buildah from --pull=never "$image")
  containers+=("$container")
  : >"$log"
  buildah run --isolation chroot --network host --volume "$volume:/var/lib/orbit" \
    "$container" -- "$@" >"$log" 2>&1 &
  pid=$!
  pids+=("$pid")
}

# The server runs as the image's user; the mounted folder must be its.
probe=$(buildah from --pull=never "$server_image")
containers+=("$probe")
uid=$(buildah run --isolation chroot --network host "$probe" -- id -u)
[[ $uid -ne 0 ]] || fail "$server_image runs as root"
chown "$uid" "$volume"

address=
start_server() {  # start_server LOG: orbit-server serve in a new container, on a free port
  run_in "$server_image" "$1" orbit-server serve --listen 127.0.0.1:0 --workers 2
  server_pid=$pid
  server_container=$container
  address=
  for _ in $(seq 600); do
    address=$(sed -n 's/.*listening on \(127\.0\.0\.1:[0-9]*\).*/\1/p' "$1" | head -1)
    [[ -n $address ]] && break
    kill -0 "$server_pid" 2>/dev/null || { cat "$1" >&2; fail "the server image did not start"; }
    sleep 0.1
  done
  [[ -n $address ]] || { cat "$1" >&2; fail "the server image did not listen within 60 s"; }
  buildah run --isolation chroot --network host "$server_container" -- \
    orbit-server info --server "$address" >"$scratch/info.txt" ||
    fail "orbit-server info in the image got no answer from $address"
}

# The processes below PID, each after its parent.
descendants() {  # descendants PID
  local child
  for child in $(pgrep -P "$1"); do
    echo "$child"
    descendants "$child"
  done
}

# Stops the server as a container engine would: SIGTERM to orbit-server, below buildah run.
stop_server() {
  local process server=
  for process in $(descendants "$server_pid"); do
    [[ $(cat "/proc/$process/comm" 2>/dev/null) == orbit-server ]] && server=$process
  done
  [[ -n $server ]] || fail "found no orbit-server process under buildah run ($server_pid)"
  kill -TERM "$server"
  wait "$server_pid" || fail "the server did not stop cleanly on SIGTERM"
}

coil_views() {  # coil_views OBJECT AZIMUTH...: --image/--azimuth arguments of COIL-100 views
  local object=$1 azimuth
  shift
  for azimuth in "$@"; do
    printf ' --image %s --azimuth %s' "$data/coil-100/obj${object}__${azimuth}.png" "$azimuth"
  done
}

recognises() {  # recognises OBJECT: views it was not enrolled from name it first
  local answer
  # shellcheck disable=SC2046  # one word per argument
  answer=$("$orbit" recognize --json --server "$address" $(coil_views "$1" 10 50 90 130) |
    tail -1)
  grep -q "\"candidates\":\[{\"id\":[0-9]*,\"name\":\"obj$1\"" <<<"$answer" ||
    fail "the server image did not recognise obj$1: $answer"
}

start_server "$scratch/server-1.log"
echo "image.sh: $server_image answers on $address"
for object in 1 2 3; do
  # shellcheck disable=SC2046
  "$orbit" enroll --server "$address" --name "obj$object" \
    $(coil_views "$object" $(seq 0 20 340)) >/dev/null
done
recognises 2
stop_server
[[ -s $volume/models.db ]] || fail "the server left no models.db on its volume"

start_server "$scratch/server-2.log"
grep -q 'objects *3' "$scratch/info.txt" ||
  { cat "$scratch/info.txt" >&2; fail "a new container on the same volume lost the objects"; }
recognises 3
echo "image.sh: a new container on the same volume holds and recognises the 3 objects"

# ---- smoke test: the balancer in front of that server ----------------------------------------
free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
balancer=127.0.0.1:$(free_port)
container=$(buildah from --pull=never "$balancer_image")
containers+=("$container")
buildah run --isolation chroot --network host \
  --env ORBIT_BALANCER_LISTEN="$balancer" --env ORBIT_REPLICA_1="$address" \
  --env ORBIT_REPLICA_2="127.0.0.1:$(free_port)" --env ORBIT_REPLICA_3="127.0.0.1:$(free_port)" \
  "$container" -- haproxy -f /etc/haproxy/orbit.cfg -db >"$scratch/balancer.log" 2>&1 &
pids+=($!)
# Replicas 2 and 3 listen nowhere: once HAProxy has marked both down, its checks have run more
# than enough times to mark replica 1 down too, had the server not answered SERVING.
marked_down() { grep -q "replica-$1 is DOWN" "$scratch/balancer.log"; }
for _ in $(seq 30); do
  marked_down 2 && marked_down 3 && break
  sleep 1
done
marked_down 2 && marked_down 3 ||
  { cat "$scratch/balancer.log" >&2; fail "the balancer ran no health check"; }
sleep 2  # two more checks of every replica
! marked_down 1 ||
  { cat "$scratch/balancer.log" >&2; fail "the balancer found the server image not serving"; }
"$orbit" info --server "$balancer" >/dev/null ||
  { cat "$scratch/balancer.log" >&2; fail "no answer through the balancer at $balancer"; }
echo "image.sh: $balancer_image checks the server's grpc.health.v1 and passes calls to it"
stop_server

# ---- sizes -----------------------------------------------------------------------------------
# An image's size as buildah lists it: its layers, unpacked, in MB of 10^6 bytes.
size_mb() {
  buildah inspect --type image --format '{{.Manifest}}' "$1" |
    python3 -c 'import json, sys
print(round(sum(layer["size"] for layer in json.load(sys.stdin)["layers"]) / 1e6))'
}
for image in debian:12-slim "$server_image" "$balancer_image"; do
  echo "image.sh: $image $(size_mb "$image") MB"
done
server_mb=$(size_mb "$server_image")
((server_mb <= max_server_mb)) ||
  fail "$server_image is $server_mb MB, over $max_server_mb MB: see what its runtime stage installs"
echo "image.sh: every image built and answered, in $((SECONDS - started)) s"
