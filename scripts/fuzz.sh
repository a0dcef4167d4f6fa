#!/usr/bin/env bash
# Fuzzes pcl::SupernodeNCutSegmentation::extract() with libFuzzer (clang, with AddressSanitizer
# and UndefinedBehaviorSanitizer) for FUZZ_SECONDS (default 60), starting from the corpus in
# test/fuzz/corpus. New inputs go to a scratch directory; FUZZ_MERGE=1 adds the ones that reach
# new code to test/fuzz/corpus. A broken invariant or a sanitizer report fails the run and
# leaves the input in build-fuzz/crash-*.
#
#   bash scripts/fuzz.sh
#
# Environment: JOBS (default 2), BUILD_DIR (default build-fuzz), FUZZ_SECONDS, FUZZ_MERGE.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
JOBS="${JOBS:-2}"
BUILD_DIR="${BUILD_DIR:-build-fuzz}"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}"

bash scripts/install_deps.sh

CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_FLAGS_DEBUG="-O1 -g" -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DPCL_NCUT_SEG_BUILD_FUZZERS=ON -DPCL_NCUT_SEG_BUILD_TESTS=OFF -DPCL_NCUT_SEG_BUILD_TOOLS=OFF
cmake --build "$BUILD_DIR" -j "$JOBS" --target fuzz_extract

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
"$BUILD_DIR/test/fuzz/fuzz_extract" "$WORK" test/fuzz/corpus \
  -max_total_time="$FUZZ_SECONDS" -max_len=800 -timeout=20 -rss_limit_mb=2048 \
  -artifact_prefix="$BUILD_DIR/" -print_final_stats=1
if [ "${FUZZ_MERGE:-0}" = 1 ]; then
  "$BUILD_DIR/test/fuzz/fuzz_extract" -merge=1 -use_counters=0 test/fuzz/corpus "$WORK"
fi
echo "scripts/fuzz.sh: no invariant broken in ${FUZZ_SECONDS} s"
