#!/usr/bin/env bash
# One report of the segmenter on every kind of input the evaluator has, on the benchmark's dev
# split and then its validation split: face centroids, area-uniform samples, noisy samples, a
# density gradient, and single views in each form a pipeline hands over (organized frame, crop,
# voxel-grid crop, laser-like samples), with the sensor origin known and unknown; and face
# centroids with the people's count given (-modes given: the cut's quality apart from the
# count; ours only, as the peers take no count). Writes
# OUT/<split>/<config>/<input>/ (the evaluator's files, its build among them) and, with
# scripts/report.py, results/report.md.
#
#   bash scripts/report.sh OUT CONFIG [evaluator flags for 'ours' ...]
#
# CONFIG names the run: "defaults" (ours with the given flags, and on views ours on the whole
# object too), "lccp" (LCCP at results/peer_settings.csv's settings, and the people against
# each other), "cpc", or any other name for ours with the given flags, e.g. "off-concavity"
# with "-concavity off".
# Environment: SPLITS (default "dev val"; each split's data is DATA_ROOT/psb-<split>, DATA_ROOT
# default ../shared/data), EVAL (the evaluator, default build/eval/pcl_ncut_seg_eval),
# PEER_SETTINGS (default results/peer_settings.csv), DRAWS (draws of the uniform samples,
# default 3), NOISY_DRAWS (of the noisy and graded samples, default 1), SAMPLES (default 20000),
# VIEWS (views per model, default 4), JOBS (evaluator runs at a time, default 2), INPUTS (a
# space-separated subset of the inputs below).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "$#" -lt 2 ]; then
  echo "usage: bash scripts/report.sh OUT CONFIG [evaluator flags]" >&2
  exit 1
fi
OUT="$1"
CONFIG="$2"
shift 2
SPLITS="${SPLITS:-dev val}"
DATA_ROOT="${DATA_ROOT:-$ROOT/../shared/data}"
PEER_SETTINGS="${PEER_SETTINGS:-$ROOT/results/peer_settings.csv}"
EVAL="${EVAL:-$ROOT/build/eval/pcl_ncut_seg_eval}"
DRAWS="${DRAWS:-3}"
NOISY_DRAWS="${NOISY_DRAWS:-1}"
SAMPLES="${SAMPLES:-20000}"
VIEWS="${VIEWS:-4}"
JOBS="${JOBS:-2}"
ALL_INPUTS="centroids samples noise_0.5 noise_1.0 density views views_unknown_origin given"
INPUTS="${INPUTS:-$ALL_INPUTS}"
for split in $SPLITS; do
  [ -d "$DATA_ROOT/psb-$split/off" ] || { echo "report.sh: no benchmark data at $DATA_ROOT/psb-$split" >&2; exit 1; }
done
[ -x "$EVAL" ] || { echo "report.sh: no evaluator at $EVAL (build it first)" >&2; exit 1; }

case "$CONFIG" in
lccp) METHODS=(-methods lccp,human -peer_settings "$PEER_SETTINGS") ;;
cpc) METHODS=(-methods cpc -peer_settings "$PEER_SETTINGS") ;;
defaults) METHODS=(-methods ours,whole) ;;
*) METHODS=(-methods ours) ;;
esac

flags_of() {
  local whole=(-modes auto) views=(-views "$VIEWS" -view_forms view,crop,voxel,laser)
  local samples=(-samples "$SAMPLES")
  case "$1" in
  centroids) echo "${whole[*]}" ;;
  given) echo "-modes given" ;;
  samples) echo "${whole[*]} ${samples[*]} -draws $DRAWS" ;;
  noise_0.5) echo "${whole[*]} ${samples[*]} -draws $NOISY_DRAWS -noise 0.5" ;;
  noise_1.0) echo "${whole[*]} ${samples[*]} -draws $NOISY_DRAWS -noise 1.0" ;;
  density) echo "${whole[*]} ${samples[*]} -draws $NOISY_DRAWS -density_ratio 4" ;;
  views) echo "${views[*]}" ;;
  views_unknown_origin) echo "${views[*]} -view_origin unknown" ;;
  *)
    echo "report.sh: unknown input '$1' (of $ALL_INPUTS)" >&2
    return 1
    ;;
  esac
}

# The peers take no count: they have no run with the count given.
peer_input() {
  [ "$1" != given ] || { [ "$CONFIG" != lccp ] && [ "$CONFIG" != cpc ]; }
}

running=0
for split in $SPLITS; do
  for input in $INPUTS; do
    peer_input "$input" || continue
    input_flags="$(flags_of "$input")"
    dir="$OUT/$split/$CONFIG/$input"
    mkdir -p "$dir"
    data="$DATA_ROOT/psb-$split"
    # shellcheck disable=SC2086  # the input's flags are words
    echo "$EVAL $data $dir -quiet ${METHODS[*]} $input_flags $*" >"$dir/command"
    rm -f "$dir/models.csv" "$dir/build"
    "$EVAL" "$data" "$dir" -quiet "${METHODS[@]}" $input_flags "$@" >"$dir/log" 2>&1 &
    running=$((running + 1))
    if [ "$running" -ge "$JOBS" ]; then
      wait -n || true
      running=$((running - 1))
    fi
  done
done
wait || true
status=0
for split in $SPLITS; do
  for input in $INPUTS; do
    peer_input "$input" || continue
    if [ ! -s "$OUT/$split/$CONFIG/$input/models.csv" ]; then
      echo "report.sh: $split/$CONFIG/$input failed: $(tail -n 1 "$OUT/$split/$CONFIG/$input/log")" >&2
      status=1
    fi
  done
done
exit "$status"
