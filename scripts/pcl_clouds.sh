#!/usr/bin/env bash
# What the tool gives on each of PCL's test clouds (../shared/data/pcl) and on the bundled
# models (data/armadillo.pcd, data/hand.pcd, as data/README.md says): points, segments,
# whether the cloud counted as one view, and the whole process' wall time, with the defaults;
# written to results/pcl_clouds.md (atomically) with the command, the build and the machine,
# and a picture of each cloud's segments from pcl_ncut_seg_viewer (off-screen, xvfb-run) in
# docs/images/pcl/ (the clouds are PCL's, BSD-3).
#
#   bash scripts/pcl_clouds.sh [OUT.md]
#
# Environment: DATA (default ../shared/data/pcl), TOOL (default build/tools/pcl_ncut_seg),
# VIEWER (default build/tools/pcl_ncut_seg_viewer; no pictures without it or xvfb-run).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATA="${DATA:-$ROOT/../shared/data/pcl}"
TOOL="${TOOL:-$ROOT/build/tools/pcl_ncut_seg}"
VIEWER="${VIEWER:-$ROOT/build/tools/pcl_ncut_seg_viewer}"
OUT="${1:-$ROOT/results/pcl_clouds.md}"
IMAGES="$ROOT/docs/images/pcl"
PICTURES=0
if [ -x "$VIEWER" ] && command -v xvfb-run > /dev/null; then
  PICTURES=1
  mkdir -p "$IMAGES"
fi
[ -d "$DATA" ] || { echo "pcl_clouds.sh: no PCL test clouds at $DATA" >&2; exit 1; }
[ -x "$TOOL" ] || { echo "pcl_clouds.sh: no tool at $TOOL (build it first)" >&2; exit 1; }

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
{
  echo "# PCL's test clouds and the bundled models"
  echo
  echo "Written by \`scripts/pcl_clouds.sh\` on $(date -u +%Y-%m-%d) with \`$(basename "$TOOL") CLOUD OUT.pcd\`" \
    "(the defaults); build $("$TOOL" -version | sed -n 's/.*(build \(.*\))$/\1/p') (the tool's own);" \
    "machine: $(nproc) cores, $(uname -sr), load average $(cut -d" " -f1-3 /proc/loadavg). Time: the whole process (read, segment, write), wall seconds."
  echo
  echo "| cloud | points | analysed | segments | view | seconds | segments (pcl_ncut_seg_viewer) |"
  echo "|---|---|---|---|---|---|---|"
  for cloud in "$DATA"/*.pcd "$ROOT"/data/*.pcd; do
    name="$(basename "$cloud")"
    start=$(date +%s.%N)
    if ! "$TOOL" "$cloud" "$WORK/out.pcd" > "$WORK/log" 2>&1; then
      echo "| $name | | | failed: $(tail -n 1 "$WORK/log") | | |"
      continue
    fi
    end=$(date +%s.%N)
    points="$(sed -n 's/^POINTS \([0-9]*\).*/\1/p' "$WORK/out.pcd" | head -n 1)"
    analysed="$(sed -n 's/^n *: \([0-9]*\) points analysed.*/\1/p' "$WORK/log")"
    segments="$(sed -n 's/^t *: \([0-9]*\) segments.*/\1/p' "$WORK/log")"
    view="$(sed -n 's/^view: //p' "$WORK/log")"
    picture=""
    png="${name%.pcd}.png"
    # Pictures of PCL's clouds only: the README shows the bundled armadillo's.
    if [ "$PICTURES" = 1 ] && [ "$(dirname "$cloud")" = "$DATA" ] &&
      xvfb-run -a "$VIEWER" "$cloud" -screenshot "$WORK/$png" -view segments -quiet \
        > "$WORK/viewer.log" 2>&1 && [ -s "$WORK/$png" ]; then
      mv "$WORK/$png" "$IMAGES/$png"
      picture="<img src=\"../docs/images/pcl/$png\" width=\"240\">"
    fi
    printf '| %s | %s | %s | %s | %s | %.2f | %s |\n' "$name" "$points" "$analysed" "$segments" \
      "$view" "$(awk "BEGIN { print $end - $start }")" "$picture"
  done
} > "$WORK/table.md"
mkdir -p "$(dirname "$OUT")"
cp "$WORK/table.md" "$OUT.tmp" && mv "$OUT.tmp" "$OUT"
echo "pcl_clouds.sh: wrote $OUT"
