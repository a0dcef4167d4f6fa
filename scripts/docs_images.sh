#!/usr/bin/env bash
# Renders the README's pictures (docs/images/) with pcl_ncut_seg_viewer, off-screen under
# xvfb-run, from a built tree. The model is CGAL's armadillo (CC0) from the project's shared
# data; MODEL=<mesh or cloud> and BUILD_DIR=<build directory> override the defaults.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD_DIR="${BUILD_DIR:-build}"
MODEL="${MODEL:-../shared/data/models/cgal-armadillo.off}"
VIEWER="$BUILD_DIR/tools/pcl_ncut_seg_viewer"

mkdir -p docs/images
for view in segments centrality supernodes refined finer; do
  xvfb-run -a "$VIEWER" "$MODEL" -samples 10000 -seed 1 -up +y -size 640x480 \
    -screenshot "docs/images/armadillo_$view.png" -view "$view" -quiet
done
ls -l docs/images
