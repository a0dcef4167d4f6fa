#!/usr/bin/env bash
# Leak and growth check: one segmenter runs extract() ITERATIONS times (default 500) on
# changing inputs; the heap in use and the resident size after the same reference input are
# compared at the start and the end. Fails when the heap grew by more than ALLOWED_KIB
# (default 128). With VALGRIND=1 it also runs a short pass (20 iterations) under valgrind
# memcheck, which fails on any definite leak or memory error (install valgrind for that).
#
#   bash scripts/leak_check.sh
#
# Environment: JOBS (default 2), BUILD_DIR (default build), ITERATIONS, ALLOWED_KIB, VALGRIND.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
JOBS="${JOBS:-2}"
BUILD_DIR="${BUILD_DIR:-build}"

bash scripts/install_deps.sh

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DPCL_NCUT_SEG_BUILD_TESTS=ON
cmake --build "$BUILD_DIR" -j "$JOBS" --target pcl_ncut_seg_leak_check
"$BUILD_DIR/test/pcl_ncut_seg_leak_check" "${ITERATIONS:-500}" "${ALLOWED_KIB:-128}"

if [ "${VALGRIND:-0}" = 1 ]; then
  # OMP_WAIT_POLICY=passive: idle OpenMP threads sleep instead of spinning under valgrind.
  OMP_WAIT_POLICY=passive valgrind --error-exitcode=1 --leak-check=full \
    --errors-for-leak-kinds=definite --show-leak-kinds=definite \
    "$BUILD_DIR/test/pcl_ncut_seg_leak_check" 20 "${ALLOWED_KIB:-128}"
fi
echo "scripts/leak_check.sh: no growth"
