#!/usr/bin/env bash
# From a fresh Debian 12 machine to a demo result: installs what the tool needs (a compiler,
# CMake, PCL; as root or with sudo), builds the pcl_ncut_seg tool in Release, and segments the
# bundled armadillo model into build/armadillo_segments.pcd; builds the project's viewer too,
# which shows the segments.
#
#   bash scripts/demo.sh
#
# Environment: JOBS (parallel jobs, default 2), BUILD_DIR (default build).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
JOBS="${JOBS:-2}"
BUILD_DIR="${BUILD_DIR:-build}"

bash scripts/install_deps.sh --tool

# Only the library and tools/: the tests, the evaluator, Python and ROS need more packages.
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DPCL_NCUT_SEG_BUILD_TOOLS=ON \
  -DPCL_NCUT_SEG_BUILD_TESTS=OFF -DPCL_NCUT_SEG_BUILD_EVAL=OFF -DPCL_NCUT_SEG_BUILD_PYTHON=OFF \
  -DPCL_NCUT_SEG_BUILD_ROS=OFF
cmake --build "$BUILD_DIR" -j "$JOBS" --target pcl_ncut_seg_tool pcl_ncut_seg_viewer

cd "$BUILD_DIR"
./tools/pcl_ncut_seg
echo
echo "Segments written to $BUILD_DIR/armadillo_segments.pcd. To see them (the viewer segments"
echo "the model with the same defaults; keys 1-4 switch between segments, centrality, supernodes):"
echo "  $BUILD_DIR/tools/pcl_ncut_seg_viewer"
echo "Without a display: $BUILD_DIR/tools/pcl_ncut_seg_viewer -screenshot armadillo.png (under xvfb-run -a)"
