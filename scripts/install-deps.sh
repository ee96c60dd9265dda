#!/usr/bin/env bash
# Installs the Debian bookworm packages fleetmap builds and tests with.
# Idempotent: asks apt only for what is missing, so a second run is a quick no-op.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  # DDS: Fast DDS 2.9, its code generator and the fastdds CLI.
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  # Geometry, images, configuration, command line, logging, JSON.
  libeigen3-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  # The m-explore baseline of `fleetmap bench register` (AKAZE, the stitching pipeline).
  libopencv-features2d-dev libopencv-flann-dev libopencv-calib3d-dev libopencv-stitching-dev
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  # Persistence and compression (LZ4: one of the fleet benchmark's byte baselines).
  libsqlite3-dev libzstd-dev zlib1g-dev libpng-dev liblz4-dev
  # DDS Security tooling (`fleetmap security`): the fleet CA, certificates, signed documents.
  libssl-dev openssl
  # The web view (`fleetmap view`): its HTTP server and the page's map library; the view's tests
  # load the page in a real browser.
  libcpp-httplib-dev libjs-leaflet chromium
  # The fuzz targets (`make fuzz`): clang and its libFuzzer, ASan and UBSan runtimes
  # (libclang-rt-14-dev holds libclang_rt.fuzzer and the sanitizers for Debian's clang 14).
  clang libclang-rt-14-dev
  # `make format-check` (.ci/run): the tree against .clang-format, with Debian's clang-format 14.
  clang-format
  # Tests and benchmarks.
  libgtest-dev libgmock-dev googletest libbenchmark-dev python3 zstd
  # Spatial indexes (Boost.Geometry R-tree, header-only).
  libboost-dev
  # Valid simple features in the GeoJSON exports (GEOS C API, common/gis).
  libgeos-dev
  # WGS84 GeoJSON (--georef): PROJ places a surveyed frame on Earth (common/gis). The tests check
  # it against PROJ's own tools (geod, cct: proj-bin) and open the files with GDAL's ogrinfo
  # (gdal-bin; with its Python bindings and numpy about 7 MB to download, 35 MB installed: GDAL's
  # library itself already comes with OpenCV's imgcodecs).
  libproj-dev proj-bin gdal-bin
  # The tests' hostile peer: a DDS participant of another vendor (Cyclone DDS and its idlc).
  cyclonedds-dev cyclonedds-tools
  # The lossy-network test and `fleetmap bench loss` (network namespaces, nftables random drop;
  # they run as root only).
  iproute2 nftables
  # The container image (scripts/build-image.sh, container_image_test): podman, runc (crun does
  # not run on these VMs' hybrid cgroups) and debootstrap for a base image without a registry.
  podman runc debootstrap
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  sudo="sudo"
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
