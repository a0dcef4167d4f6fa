#!/usr/bin/env bash
# From a fresh Debian 12 machine to passing tests: installs the dependencies (as root or with
# sudo), builds in Release into build/, runs every test, then installs into a temporary prefix
# and builds and runs a small downstream project that uses find_package(pcl_ncut_seg).
#
#   bash scripts/test.sh
#
# Environment: JOBS (parallel jobs, default 2), BUILD_DIR (default build).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
JOBS="${JOBS:-2}"
BUILD_DIR="${BUILD_DIR:-build}"

bash scripts/install_deps.sh

# Every part named ON, so that a build directory configured by scripts/demo.sh (the tool alone)
# gets them all back. Python and ROS are still skipped with a message when pybind11 or ROS 1
# is missing.
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release \
  -DPCL_NCUT_SEG_BUILD_TESTS=ON -DPCL_NCUT_SEG_BUILD_TOOLS=ON -DPCL_NCUT_SEG_BUILD_EVAL=ON \
  -DPCL_NCUT_SEG_BUILD_PYTHON=ON -DPCL_NCUT_SEG_BUILD_ROS=ON
cmake --build "$BUILD_DIR" -j "$JOBS"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS"

# The installed package, as a downstream project sees it.
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cmake --install "$BUILD_DIR" --prefix "$WORK/prefix"
cmake -S test/consumer -B "$WORK/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$WORK/prefix"
cmake --build "$WORK/consumer" -j "$JOBS"
"$WORK/consumer/pcl_ncut_seg_consumer"
# The installed Python package imports and segments (when pybind11 was found).
PY_MODULE="$(find "$WORK/prefix" -name '_pcl_ncut_seg.cpython-*.so' | head -n 1)"
if [ -n "$PY_MODULE" ]; then
  PYTHON="$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt")"
  test -s "$(dirname "$PY_MODULE")/__init__.pyi" && test -e "$(dirname "$PY_MODULE")/py.typed"
  PYTHONPATH="$(dirname "$(dirname "$PY_MODULE")")" "$PYTHON" -c 'import numpy, pcl_ncut_seg
labels = pcl_ncut_seg.segment(numpy.random.default_rng(1).normal(size=(500, 3)), segments=2)
assert labels.shape == (500,) and labels.max() == 2, labels'
fi
# The installed tool finds the installed model.
(cd "$WORK" && "$WORK/prefix/bin/pcl_ncut_seg" -quiet -segments 2 && test -s armadillo_segments.pcd)

echo "scripts/test.sh: all tests passed"
