#!/usr/bin/env bash
# Speed: runs the programs of bench/ that time the whole segmenter beside PCL's supervoxels +
# LCCP (Table 1, the depth views, and PCD file to file at four sizes), and writes what they
# print to results/speed.md (atomically), with the commands, the build, the machine and its
# load at the top. Figures are wall seconds as each program measured them; a loaded machine
# makes them slower, so read the load first.
#
#   bash scripts/bench.sh [OUT.md]
#
# Environment: BUILD_DIR (a build configured with -DPCL_NCUT_SEG_BUILD_BENCH=ON, default
# build), QUICK=1 (pcl_ncut_seg_bench --quick: Table 1's smaller sizes only; the sizes bench
# always runs up to 10M points).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
OUT="${1:-$ROOT/results/speed.md}"
BENCH="$BUILD_DIR/bench"
for program in pcl_ncut_seg_bench pcl_ncut_seg_bench_views pcl_ncut_seg_bench_sizes; do
  [ -x "$BENCH/$program" ] || {
    echo "bench.sh: no $BENCH/$program (configure with -DPCL_NCUT_SEG_BUILD_BENCH=ON and build)" >&2
    exit 1
  }
done
[ -d "$ROOT/../shared/data/models" ] || { echo "bench.sh: no ../shared/data/models" >&2; exit 1; }

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
TABLE1=("$BENCH/pcl_ncut_seg_bench")
[ "${QUICK:-0}" = 1 ] && TABLE1+=(--quick)
VIEWS=("$BENCH/pcl_ncut_seg_bench_views")
SIZES=("$BENCH/pcl_ncut_seg_bench_sizes") # 10M points included: about a minute
{
  echo "# Speed"
  echo
  echo "Written by \`scripts/bench.sh\` on $(date -u +%Y-%m-%d); each program prints its own" \
    "build on its first line; machine:" \
    "$(nproc) cores ($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1))," \
    "$(uname -sr); load average before the runs $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  for run in TABLE1 VIEWS SIZES; do
    declare -n cmd="$run"
    title="$(basename "${cmd[0]}")"
    [ "${#cmd[@]}" -gt 1 ] && title="$title ${cmd[*]:1}"
    echo "## \`$title\`"
    echo
    echo '```'
    "${cmd[@]}" 2>&1
    echo '```'
    echo
  done
} > "$WORK/speed.md"
mkdir -p "$(dirname "$OUT")"
cp "$WORK/speed.md" "$OUT.tmp" && mv "$OUT.tmp" "$OUT"
echo "bench.sh: wrote $OUT"
