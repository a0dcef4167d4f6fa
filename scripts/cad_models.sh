#!/usr/bin/env bash
# Segment the CAD parts of the shared data in CAD mode (-cad) and print the segment counts.
#
#   bash scripts/cad_models.sh [build dir] [output dir]
#
# Samples N points (env N, default 20000, seed fixed by the sampler) on each mesh of
# ../shared/data/models (or $DATA/models) with pcl_ncut_seg_sample_mesh, segments them with
# pcl_ncut_seg -cad, and writes <model>.pcd and <model>_cad.pcd into the output directory
# (default build/cad_models). Prints one line per model: points, supernodes, segments, time,
# and writes the same as a Markdown table, with the command, the build and the machine at its
# top, to results/cad_models.md (env RESULTS; atomically).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$build/cad_models}"
data="${DATA:-$here/../shared/data}"
n="${N:-20000}"
results="${RESULTS:-$here/results/cad_models.md}"
models=(block cgal-fandisk cgal-joint cgal-rotor cgal-anchor cgal-cube-meshed)

sampler="$build/tools/pcl_ncut_seg_sample_mesh"
tool="$build/tools/pcl_ncut_seg"
for exe in "$sampler" "$tool"; do
  [[ -x "$exe" ]] || { echo "missing $exe: build the tools first" >&2; exit 1; }
done
[[ -d "$data/models" ]] || { echo "no models in $data/models" >&2; exit 1; }
mkdir -p "$out"

table="$(mktemp)"
trap 'rm -f "$table"' EXIT
printf '%-18s %8s %6s %6s %9s %8s\n' model points m l segments total_s
for model in "${models[@]}"; do
  mesh="$data/models/$model.off"
  [[ -f "$mesh" ]] || { echo "skipping $model: no $mesh" >&2; continue; }
  "$sampler" "$mesh" "$out/$model.pcd" -n "$n" >/dev/null
  log="$("$tool" "$out/$model.pcd" "$out/${model}_cad.pcd" -cad)"
  field() { awk -v key="$1" '$1 == key { print ($1 == "total:" ? $2 : $3) }' <<<"$log"; }
  printf '%-18s %8s %6s %6s %9s %8s\n' "$model" "$(field n)" "$(field m)" "$(field l)" \
    "$(field t)" "$(field total:)"
  printf '| %s | %s | %s | %s | %s | %s |\n' "$model" "$(field n)" "$(field m)" "$(field l)" \
    "$(field t)" "$(field total:)" >> "$table"
done

mkdir -p "$(dirname "$results")"
{
  echo "# CAD parts of the shared data in CAD mode"
  echo
  echo "Written by \`scripts/cad_models.sh\` on $(date -u +%Y-%m-%d): each mesh of" \
    "\`../shared/data/models\` sampled with \`pcl_ncut_seg_sample_mesh MODEL.off MODEL.pcd -n $n\`," \
    "then \`pcl_ncut_seg MODEL.pcd MODEL_cad.pcd -cad\` (the defaults otherwise); build" \
    "$("$tool" -version | sed -n 's/.*(build \(.*\))$/\1/p') (the tools in \`$(realpath --relative-to="$here" "$build")\`);" \
    "machine: $(nproc) cores, $(uname -sr). The meshes have no face labels: apart from the meshed" \
    "cube (six faces, tested) the counts are not checked against a truth."
  echo
  echo "| model | points n | supernodes m | after refinement and ridge split l | segments t | total s |"
  echo "|---|---|---|---|---|---|"
  cat "$table"
} > "$results.tmp"
mv "$results.tmp" "$results"
echo "cad_models.sh: wrote $results"

