#!/usr/bin/env bash
# The CLI's labels on the bundled models, the shared models and PCL's clouds, in default, -paper,
# -cad and -exact runs, one checksum per run: a structural change that must not change what the
# segmenter outputs is checked by comparing the file this writes before and after it.
#
#   bash scripts/label_check.sh OUT_FILE [CLI]
#
# CLI: default build/tools/pcl_ncut_seg. Models absent from ../shared/data are left out.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:?usage: bash scripts/label_check.sh OUT_FILE [CLI]}"
CLI="${2:-$ROOT/build/tools/pcl_ncut_seg}"
DATA="$ROOT/../shared/data"
[ -x "$CLI" ] || { echo "label_check.sh: no tool at $CLI (build it first)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
inputs=("$ROOT"/data/*.pcd)
for f in "$DATA"/models/*.off "$DATA"/pcl/*.pcd; do [ -f "$f" ] && inputs+=("$f"); done
: >"$work/sums"
for input in "${inputs[@]}"; do
  for config in "" "-paper" "-cad" "-exact" "-samples 20000"; do
    case "$config:$input" in -samples*:*.pcd) continue ;; esac
    # shellcheck disable=SC2086  # the configuration's flags are words
    "$CLI" "$input" "$work/out.pcd" -ascii $config -threads 1 >"$work/log" 2>&1 ||
      { echo "label_check.sh: $input $config failed: $(tail -n 1 "$work/log")" >&2; exit 1; }
    # The labels alone (the last field), not the colours or the header's version line.
    sum="$(sed '1,/^DATA/d' "$work/out.pcd" | awk '{print $NF}' | md5sum | cut -d' ' -f1)"
    echo "$(basename "$input") ${config:-defaults} $sum" >>"$work/sums"
  done
done
mv "$work/sums" "$OUT"
