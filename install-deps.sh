#!/usr/bin/env bash
# Installs the Debian 12 packages claspplan builds with. Idempotent: packages already present are skipped.
set -euo pipefail

packages=(
  build-essential cmake ccache pkg-config
  libvisp-dev libeigen3-dev libpcl-dev libfcl-dev liburdfdom-dev libopencv-dev
  libcgal-dev libgmp-dev libmpfr-dev     # exact 3-D Delaunay triangulation (perception)
  libnanoflann-dev                       # k-d trees (perception, TS-RRT nearest neighbours)
  libpng-dev                             # PNG files without OpenCV's codecs (~140 libraries fewer)
  libcli11-dev nlohmann-json3-dev libyaml-cpp-dev   # command line, JSON output, YAML files
  libompl-dev                            # OMPL's RRTConnect: the benchmark's two-phase baseline
  liboctomap-dev                         # the sensed space as an OcTree, collided by FCL (robots)
  libassimp-dev                          # COLLADA (.dae) collision meshes of public URDFs (robots)
  libqhull-dev                           # convex hulls of robot meshes (robots, collision.mesh_hulls)
  python3-dev pybind11-dev python3-numpy # the Python package (examples/python)
  python3-pytest python3-matplotlib      # its tests and examples
  python3-venv python3-pip               # `pip install .` checked in a virtual environment (.ci/pip.sh)
  libgtest-dev libbenchmark-dev          # tests and kernel benchmarks
  clang-14 libclang-rt-14-dev            # libFuzzer targets (test/fuzz, .ci/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
