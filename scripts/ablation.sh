#!/usr/bin/env bash
# The ablation: scripts/report.sh with every stage at its default (OUT/<split>/base/), then once
# per extension and detector with that stage off and everything else at its default, into
# OUT/<split>/off-<stage>/, on the dev and validation splits (report.sh's SPLITS);
# `scripts/report.py REPORT_OUT results/report.md OUT` then writes what each stage changes to
# results/ablation.md. Stages that act only on open views run on the views alone.
#
#   bash scripts/ablation.sh OUT [stage ...]
#
# Environment: as scripts/report.sh, SKIP_BASE=1 to keep an earlier OUT/base, WHOLE_INPUTS and
# VIEW_INPUTS (the inputs of the stages that act on any input, and on views only); its defaults here are DRAWS=1 and VIEWS=2, and the inputs
# leave out the samples with noise of 0.5 spacings (the same kind of input as 1.0). The
# stages run by default are those that change labels; fast_centrality (a speed stage, within
# 1-2% of the exact f) is measured only when named.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:?usage: bash scripts/ablation.sh OUT [stage ...]}"
shift
export DRAWS="${DRAWS:-1}" VIEWS="${VIEWS:-2}"
WHOLE="${WHOLE_INPUTS:-centroids samples noise_1.0 density views views_unknown_origin}"
VIEWS_ONLY="${VIEW_INPUTS:-views views_unknown_origin}"

# stage: its flags when off, and which inputs it can act on.
declare -A OFF=(
  [bridge_gap]="-bridge_gap off"
  [denoise]="-denoise off"
  [irregular_sampling]="-irregular_sampling off"
  [fast_centrality]="-centrality exact"
  [starts]="-starts 1"
  [crease_split]="-crease_split off"
  [normalize_width]="-normalize_width off"
  [adjacency]="-adjacency saddles"
  [concavity]="-concavity off"
  [flat_elongation]="-flat_elongation off"
  [short_cut]="-stopping threshold"
  [boundary_band]="-boundary_band off"
  [rim_merge]="-rim_merge off"
  [single_view]="-single_view off"
)
declare -A ON_VIEWS_ONLY=([rim_merge]=1 [single_view]=1)
ORDER="bridge_gap denoise irregular_sampling starts crease_split normalize_width
adjacency concavity flat_elongation short_cut boundary_band rim_merge single_view"

stages=("$@")
[ "${#stages[@]}" -gt 0 ] || read -r -a stages <<<"$(echo $ORDER)"
status=0
# The baseline at the same draws and views: every stage at its default.
if [ -z "${SKIP_BASE:-}" ]; then
  echo "ablation.sh: the defaults ($WHOLE)"
  INPUTS="$WHOLE" bash "$ROOT/scripts/report.sh" "$OUT" base || status=1
fi
for stage in "${stages[@]}"; do
  [ -n "${OFF[$stage]:-}" ] || { echo "ablation.sh: unknown stage '$stage'" >&2; exit 1; }
  inputs="$WHOLE"
  [ -z "${ON_VIEWS_ONLY[$stage]:-}" ] || inputs="$VIEWS_ONLY"
  echo "ablation.sh: $stage off ($inputs)"
  # shellcheck disable=SC2086  # the flags are words
  INPUTS="$inputs" bash "$ROOT/scripts/report.sh" "$OUT" "off-$stage" ${OFF[$stage]} || status=1
done
exit "$status"
