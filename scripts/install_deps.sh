#!/usr/bin/env bash
# Installs the dependencies on Debian 12 (or a close relative) with apt-get. Does nothing when
# they are all installed already. Needs root, or sudo.
#
#   bash scripts/install_deps.sh          # everything the build, the tests and CI need
#   bash scripts/install_deps.sh --tool   # only the library and the command-line tools
#                                         # (scripts/demo.sh): a compiler, CMake and PCL
set -euo pipefail

# The library and tools/: PCL (with Eigen, FLANN, Boost, and VTK for the viewer), CMake, g++.
TOOL_PACKAGES=(
  build-essential cmake
  libpcl-dev libeigen3-dev libflann-dev libboost-graph-dev
)
# The tests, the lab and the other front ends (scripts/test.sh, .ci/run).
FULL_PACKAGES=(
  libgtest-dev
  python3-dev python3-pybind11 python3-numpy python3-pytest   # the Python module and its tests
  python3-open3d python3-mypy      # the Open3D tests and example; the stub checked by mypy, stubtest
  python3-distributed python3-dask python3-tqdm   # python -m pcl_ncut_seg.batch and its tests
  python3-venv python3-pip python3-setuptools python3-wheel ccache   # scripts/python_package.sh
  pcl-tools xvfb xauth
  clang libclang-rt-dev libomp-dev   # scripts/fuzz.sh: libFuzzer, sanitizer runtimes, OpenMP
  # ROS 1 (ros/: the nodelet, the node, their rostests; the README's ROS section)
  catkin libroscpp-dev rosout python3-rosmaster python3-roslaunch python3-rostopic python3-rosnode
  libnodeletlib-dev libnodeletlib-tools libnodelet-topic-tools-dev libmessage-filters-dev
  libsensor-msgs-dev python3-sensor-msgs libstd-msgs-dev python3-std-msgs
  libpcl-conversions-dev libpcl-ros-dev pcl-ros-tools python3-pcl-msgs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  rospack-tools rosbash python3-rostest librostest-dev
  libtf2-ros-dev tf2-tools   # ~sensor_frame; its rostest's static_transform_publisher
)

case "${1:-}" in
  "") PACKAGES=("${TOOL_PACKAGES[@]}" "${FULL_PACKAGES[@]}") ;;
  --tool) PACKAGES=("${TOOL_PACKAGES[@]}") ;;
  *) echo "usage: $0 [--tool]" >&2; exit 2 ;;
esac

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all dependencies are installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "install_deps: missing packages: ${missing[*]}" >&2
  echo "install_deps: run as root, or install sudo, or install them yourself" >&2
  exit 1
fi

echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${PACKAGES[@]}"
