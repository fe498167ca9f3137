#!/bin/bash
# Issue 21, section 5: the void morphology of every paper-size checkpoint of a shape (aniso-voxel at
# the config's 20 voxels per d50) and, for the checkpoints named in LBM_STEMS, the permeability
# tensor (aniso-lbm, three flow directions). What is done is skipped, so an interrupted run resumes.
# usage: workflows/voids_and_flow.sh SHAPE   (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)
#   reads runs/paper-SHAPE/load_0*.h5, writes runs/paper-SHAPE/voxel/ and runs/paper-SHAPE/lbm/
#   BIN=<build dir> (default build), RANKS=<MPI ranks for the LBM> (default 2),
#   LBM_STEMS="load_000 load_019" (default none), LBM_ARGS adds --set options to the LBM.
# Then workflows/plots/paper_voids_csv.py runs/paper-SHAPE docs/paper-size/SHAPE writes the committed CSVs.
set -euo pipefail
cd "$(dirname "$0")/.."  # the repository root
shape=${1:?usage: workflows/voids_and_flow.sh SHAPE (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)}
run=runs/paper-$shape
config=workflows/configs/paper-$shape.toml
bin=${BIN:-build}
ranks=${RANKS:-2}
[ -f "$config" ] || { echo "voids_and_flow.sh: no config $config" >&2; exit 2; }
compgen -G "$run/load_0*.h5" > /dev/null || { echo "voids_and_flow.sh: no checkpoints $run/load_0*.h5" >&2; exit 2; }
mkdir -p "$run/voxel" "$run/lbm"
for checkpoint in "$run"/load_0*.h5; do
  stem=$(basename "$checkpoint" .h5)
  [ -f "$run/voxel/voids_$stem.h5" ] && continue
  start=$(date +%s)
  "$bin/voxel/aniso-voxel" --config "$config" --set voxel.output_dir="$run/voxel" --input "$checkpoint" \
    --log-level info > "$run/voxel/voxel_$stem.log" 2>&1 ||
    { echo "voids_and_flow.sh: aniso-voxel failed on $checkpoint; see $run/voxel/voxel_$stem.log" >&2; exit 1; }
  echo "$stem voxel $(($(date +%s) - start)) s load $(cut -d' ' -f1-3 /proc/loadavg)" >> "$run/times.log"
done
for stem in ${LBM_STEMS:-}; do
  result=$run/lbm/permeability_image_$stem.h5
  [ -f "$result" ] && continue
  start=$(date +%s)
  # shellcheck disable=SC2086 # LBM_ARGS is a list of options
  mpirun -np "$ranks" "$bin/lbm/aniso-lbm" --config "$config" --set lbm.output_dir="$run/lbm" ${LBM_ARGS:-} \
    --input "$run/voxel/image_$stem.h5" --log-level info > "$run/lbm/lbm_$stem.log" 2>&1 ||
    { echo "voids_and_flow.sh: aniso-lbm failed on $stem; see $run/lbm/lbm_$stem.log" >&2; exit 1; }
  echo "$stem lbm $(($(date +%s) - start)) s on $ranks ranks load $(cut -d' ' -f1-3 /proc/loadavg)" >> "$run/times.log"
done
