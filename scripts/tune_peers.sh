#!/usr/bin/env bash
# LCCP's and CPC's settings as a user would tune them on the dev split: a grid of the smallest
# segment (supervoxels) and the seed resolution, on the face centroids, on 20k area-uniform
# samples and on views (crop, voxel-grid crop, laser-like; the organized frame's valid points
# are the crop's). Writes OUT/<input>_ms<N>_s<F>/ and, with scripts/tune_peers.py,
# results/peers.md, whose best settings scripts/report.sh uses.
#
#   bash scripts/tune_peers.sh OUT
#
# Environment: DATA, EVAL (as scripts/report.sh), VIEWS (default 2).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:?usage: bash scripts/tune_peers.sh OUT}"
DATA="${DATA:-$ROOT/../shared/data/psb-dev}"
EVAL="${EVAL:-$ROOT/build/eval/pcl_ncut_seg_eval}"
VIEWS="${VIEWS:-2}"

for ms in 0 3 10; do
  for seed in 0.05 0.1; do
    peer=(-methods lccp,cpc -peer_min_segment "$ms" -peer_seed "$seed")
    for input in views cent samp; do
      case "$input" in
      views) flags=(-views "$VIEWS" -view_forms crop,voxel,laser) ;;
      cent) flags=(-modes auto) ;;
      samp) flags=(-modes auto -samples 20000) ;;
      esac
      dir="$OUT/${input}_ms${ms}_s${seed}"
      mkdir -p "$dir"
      echo "$EVAL $DATA $dir -quiet ${peer[*]} ${flags[*]}" >"$dir/command"
      "$EVAL" "$DATA" "$dir" -quiet "${peer[@]}" "${flags[@]}" >"$dir/log" 2>&1
    done
  done
done
