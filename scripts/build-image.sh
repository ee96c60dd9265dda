#!/usr/bin/env bash
# Builds the container image `fleetmap:<version>` (docker/Dockerfile) with podman, from the Debian
# package of BUILD_DIR, on machines that reach the Debian mirror but no container registry:
#   1. a bookworm base image made by debootstrap (minbase) and imported as
#      localhost/fleetmap-base:bookworm, once (reused while it exists);
#   2. the package: cmake --build BUILD_DIR --target package;
#   3. podman build with that base; the build's RUN steps use chroot isolation, which needs no
#      OCI runtime.
# It also writes BUILD_DIR/containers.conf for running the image here: these VMs refuse the OCI
# runtimes' default rlimits (podman 4.3 asks for 1048576 open files, over the VM's hard limit) and
# crun refuses their hybrid cgroups, so it names runc and rlimits within this machine's.
#   CONTAINERS_CONF=$PWD/BUILD_DIR/containers.conf podman run --rm localhost/fleetmap fleetmap --version
# docs/building.md, "Containers". Usage: scripts/build-image.sh [BUILD_DIR]
set -euo pipefail

build_dir=${1:-build}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
base=localhost/fleetmap-base:bookworm
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}

for tool in podman debootstrap runc; do
  command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || {
    echo "build-image: $tool is missing (scripts/install-deps.sh installs it)" >&2
    exit 1
  }
done

conf="$build_dir/containers.conf"
nofile=$(ulimit -Hn)
[ "$nofile" = unlimited ] || [ "$nofile" -gt 65536 ] && nofile=65536
nproc=$(ulimit -Hu)
[ "$nproc" = unlimited ] || [ "$nproc" -gt 32768 ] && nproc=32768
mkdir -p "$build_dir"
cat > "$conf" <<EOF
# Written by scripts/build-image.sh for this machine: runc, and rlimits within its hard limits.
[containers]
default_ulimits = ["nofile=$nofile:$nofile", "nproc=$nproc:$nproc"]
[engine]
runtime = "runc"
EOF
export CONTAINERS_CONF=$(realpath "$conf")

if ! podman image exists "$base"; then
  echo "build-image: making the bookworm base with debootstrap from $mirror (about a minute)"
  rootfs=$(mktemp -d /var/tmp/fleetmap-base.XXXXXX)
  trap 'rm -rf "$rootfs"' EXIT
  debootstrap --variant=minbase bookworm "$rootfs" "$mirror" > "$rootfs.log" 2>&1 || {
    echo "build-image: debootstrap failed; its log: $rootfs.log" >&2
    exit 1
  }
  tar -C "$rootfs" -c . | podman import --quiet - "$base" > /dev/null
  rm -f "$rootfs.log"
fi

echo "build-image: the Debian package"
cmake --build "$build_dir" --target package > /dev/null
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build_dir/CMakeCache.txt")
deb="$build_dir/packages/fleetmap_${version}_amd64.deb"
[ -f "$deb" ] || { echo "build-image: no $deb after the package target" >&2; exit 1; }

# The context is the package alone, copied into an empty folder: the build directory holds
# gigabytes, and maybe packages of other versions.
context=$(mktemp -d /var/tmp/fleetmap-context.XXXXXX)
mkdir -p "$context/build/packages"
cp "$deb" "$context/build/packages/"
echo "build-image: podman build fleetmap:$version"
podman build --quiet --isolation chroot --build-arg "BASE=$base" \
  -f "$source_dir/docker/Dockerfile" -t "fleetmap:$version" -t fleetmap:latest "$context" > /dev/null
rm -rf "$context"
echo "build-image: fleetmap:$version built; run it with CONTAINERS_CONF=$CONTAINERS_CONF podman run localhost/fleetmap:$version ..."
