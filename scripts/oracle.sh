#!/usr/bin/env bash
# Issue 63's diagnostic: the gap to people in two parts. On the dev split (both halves) and the
# validation split, face centroids, per category: ours at its defaults, the people against
# each other, the finest level as it is, the finest-level oracle (each segment of ours asked for
# ORACLE_SEGMENTS parts merged into the person's segment it overlaps most, per person) and its
# control (the same merge of k-means with as many segments). Then scripts/oracle.py writes
# results/oracle.md.
#
#   bash scripts/oracle.sh OUT [evaluator flags for 'ours' ...]
#
# THE ORACLES READ THE PEOPLE'S SEGMENTATIONS: they bound what a choice among the finest
# level's boundaries could reach. No default may be chosen by them.
# Writes OUT/<split>/oracle/centroids/ (the evaluator's files, its build, its command relative
# to the repository, its wall time in seconds). Environment: SPLITS (default "dev val"),
# DATA_ROOT (default ../shared/data), EVAL (default build/eval/pcl_ncut_seg_eval),
# ORACLE_SEGMENTS (default 30), JOBS (runs at a time, default 1), REPORT (default
# results/oracle.md; "none": no file).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:?usage: bash scripts/oracle.sh OUT [evaluator flags]}"
shift
SPLITS="${SPLITS:-dev val}"
DATA_ROOT="${DATA_ROOT:-$ROOT/../shared/data}"
EVAL="${EVAL:-$ROOT/build/eval/pcl_ncut_seg_eval}"
ORACLE_SEGMENTS="${ORACLE_SEGMENTS:-30}"
JOBS="${JOBS:-1}"
REPORT="${REPORT:-$ROOT/results/oracle.md}"
for split in $SPLITS; do
  [ -d "$DATA_ROOT/psb-$split/off" ] || { echo "oracle.sh: no benchmark data at $DATA_ROOT/psb-$split" >&2; exit 1; }
done
[ -x "$EVAL" ] || { echo "oracle.sh: no evaluator at $EVAL (build it first)" >&2; exit 1; }

rel() { realpath -m --relative-to="$ROOT" "$1"; }
# shellcheck disable=SC2054  # the methods are one comma-separated word
FLAGS=(-quiet -methods ours,human,finest,oracle,kmeans_oracle -modes auto
  -oracle_segments "$ORACLE_SEGMENTS")

run_split() {
  local split="$1" dir="$OUT/$1/oracle/centroids" data="$DATA_ROOT/psb-$1"
  shift
  mkdir -p "$dir"
  rm -f "$dir/models.csv" "$dir/build" "$dir/seconds"
  echo "$(rel "$EVAL") $(rel "$data") $(rel "$dir") ${FLAGS[*]} $*" >"$dir/command"
  local start end
  start=$(date +%s.%N)
  "$EVAL" "$data" "$dir" "${FLAGS[@]}" "$@" >"$dir/log" 2>&1
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f\n", b - a }' >"$dir/seconds"
}

running=0
for split in $SPLITS; do
  run_split "$split" "$@" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true
status=0
for split in $SPLITS; do
  if [ ! -s "$OUT/$split/oracle/centroids/models.csv" ]; then
    echo "oracle.sh: $split failed: $(tail -n 1 "$OUT/$split/oracle/centroids/log")" >&2
    status=1
  fi
done
[ "$status" -eq 0 ] || exit "$status"
[ "$REPORT" = none ] || python3 "$ROOT/scripts/oracle.py" "$OUT" "$REPORT"
