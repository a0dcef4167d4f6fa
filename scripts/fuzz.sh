#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang, with AddressSanitizer and UndefinedBehaviorSanitizer), each
# target for FUZZ_SECONDS (default 60), starting from its corpus:
#   fuzz_extract  pcl::SupernodeNCutSegmentation::extract()   test/fuzz/corpus
#   fuzz_read     the tools' reader of files (kit/files)       test/fuzz/corpus_read
# New inputs go to a scratch directory; FUZZ_MERGE=1 adds the ones that reach new code to the
# target's corpus. A broken invariant or a sanitizer report fails the run and leaves the input
# in build-fuzz/<target>-crash-*.
#
#   bash scripts/fuzz.sh [target...]     # default: every target, one after the other
#
# Environment: JOBS (default 2), BUILD_DIR (default build-fuzz), FUZZ_SECONDS, FUZZ_MERGE.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
JOBS="${JOBS:-2}"
BUILD_DIR="${BUILD_DIR:-build-fuzz}"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}"

corpus() { case "$1" in fuzz_extract) echo test/fuzz/corpus ;; fuzz_read) echo test/fuzz/corpus_read ;; esac; }
max_len() { case "$1" in fuzz_extract) echo 800 ;; fuzz_read) echo 8192 ;; esac; }

TARGETS=("$@")
[ "${#TARGETS[@]}" -gt 0 ] || TARGETS=(fuzz_extract fuzz_read)
for target in "${TARGETS[@]}"; do
  if [ -z "$(corpus "$target")" ]; then
    echo "scripts/fuzz.sh: no fuzz target '$target' (fuzz_extract, fuzz_read)" >&2
    exit 2
  fi
done

bash scripts/install_deps.sh

CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_FLAGS_DEBUG="-O1 -g" -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DPCL_NCUT_SEG_BUILD_FUZZERS=ON -DPCL_NCUT_SEG_BUILD_TESTS=OFF -DPCL_NCUT_SEG_BUILD_TOOLS=OFF
cmake --build "$BUILD_DIR" -j "$JOBS" --target "${TARGETS[@]}"

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for target in "${TARGETS[@]}"; do
  mkdir -p "$WORK/$target"
  "$BUILD_DIR/test/fuzz/$target" "$WORK/$target" "$(corpus "$target")" \
    -max_total_time="$FUZZ_SECONDS" -max_len="$(max_len "$target")" -timeout=20 \
    -rss_limit_mb=2048 -artifact_prefix="$BUILD_DIR/$target-" -print_final_stats=1
  if [ "${FUZZ_MERGE:-0}" = 1 ]; then
    "$BUILD_DIR/test/fuzz/$target" -merge=1 -use_counters=0 "$(corpus "$target")" "$WORK/$target"
  fi
  echo "scripts/fuzz.sh: $target broke no invariant in ${FUZZ_SECONDS} s"
done
