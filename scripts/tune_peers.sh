#!/usr/bin/env bash
# LCCP's and CPC's settings as a user would tune them: the grid of scripts/tune_peers.py on the
# dev split, the chosen settings run once on the validation split, and results/peers.md.
#
#   bash scripts/tune_peers.sh OUT [peers.md]
#
# Environment: as scripts/tune_peers.py (EVAL, DEV, VAL, JOBS). It also writes
# results/peer_settings.csv, the settings scripts/report.sh and bench/ run the peers with.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:?usage: bash scripts/tune_peers.sh OUT [peers.md]}"
/usr/bin/python3 "$ROOT/scripts/tune_peers.py" run "$OUT"
/usr/bin/python3 "$ROOT/scripts/tune_peers.py" write "$OUT" "${2:-$ROOT/results/peers.md}"
