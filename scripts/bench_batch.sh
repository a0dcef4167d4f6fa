#!/usr/bin/env bash
# The batch front end's speed: files per second of `python -m pcl_ncut_seg.batch` on 1, 2 and
# all cores against a shell loop over the pcl_ncut_seg tool, on the same folder (the first
# FILES meshes of ../shared/data/psb-dev), every run's outputs checked to be the loop's byte for
# byte (python/benchmarks/bench_batch.py). Writes results/batch.md (atomically) with the
# command, the build, the machine and its load: a loaded machine is slower, read the load first.
#
#   bash scripts/bench_batch.sh [OUT.md]
#
# Environment: BUILD_DIR (a build with the tool and the Python module, default build), FILES
# (how many meshes, default 40), FLAGS (the tool's flags for both, default none), PYTHON
# (default /usr/bin/python3).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
OUT="${1:-$ROOT/results/batch.md}"
PYTHON="${PYTHON:-/usr/bin/python3}"
FILES="${FILES:-40}"
TOOL="$BUILD_DIR/tools/pcl_ncut_seg"
DATA="$ROOT/../shared/data/psb-dev/off"
[ -x "$TOOL" ] || { echo "bench_batch.sh: no $TOOL (build the target pcl_ncut_seg_tool)" >&2; exit 1; }
[ -d "$BUILD_DIR/python/pcl_ncut_seg" ] || {
  echo "bench_batch.sh: no $BUILD_DIR/python/pcl_ncut_seg (build pcl_ncut_seg_python_package)" >&2
  exit 1
}
[ -d "$DATA" ] || { echo "bench_batch.sh: no $DATA" >&2; exit 1; }
read -r -a flags <<<"${FLAGS:-}"

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
{
  echo "# The batch front end's speed"
  echo
  echo "Written by \`scripts/bench_batch.sh\` (FILES=$FILES) on $(date -u +%Y-%m-%d); build" \
    "$(git -C "$ROOT" describe --always --dirty 2>/dev/null || echo unknown); machine:" \
    "$(nproc) cores ($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1))," \
    "$(uname -sr); load average before the runs $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "Inputs: the first $FILES meshes of ../shared/data/psb-dev by name (a point per face)." \
    "Seconds are wall seconds of the whole command, the local cluster's start-up included."
  echo
  PYTHONPATH="$BUILD_DIR/python" "$PYTHON" "$ROOT/python/benchmarks/bench_batch.py" \
    "$TOOL" "$DATA" "$FILES" -- "${flags[@]}"
} >"$WORK/batch.md"
mkdir -p "$(dirname "$OUT")"
cp "$WORK/batch.md" "$OUT.tmp" && mv "$OUT.tmp" "$OUT"
echo "bench_batch.sh: wrote $OUT"
