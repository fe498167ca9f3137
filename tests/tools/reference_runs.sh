#!/usr/bin/env bash
# Runs a fixed set of small DEM and probe scenarios into a folder, so that two builds (two
# commits) can be compared bit for bit with tests/workflows/compare_runs.py: a refactoring
# that claims "the same bits" proves it with
#
#   tests/tools/reference_runs.sh OLD_BUILD runs/ref-old
#   tests/tools/reference_runs.sh NEW_BUILD runs/ref-new
#   /usr/bin/python3 tests/workflows/compare_runs.py runs/ref-old runs/ref-new
#
# usage: reference_runs.sh BUILD_DIR WORK_DIR
# About 6 minutes on 2 cores. Every scenario exercises a protocol: prepare (two compaction
# cycles, consolidation), load (continuous, with relaxed checkpoints; OVAL's relaxed
# increments), a resume from a checkpoint, relax, hold, probe (all seven forks), on 1 and 2 ranks,
# for spheres and ovoids. Logs go to WORK_DIR/logs/ (not compared).
set -euo pipefail
build=$(cd "$1" && pwd) work=$2
rm -rf "$work"
mkdir -p "$work/logs"
work=$(cd "$work" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
dem=$build/dem/aniso-dem probe=$build/probe/aniso-probe
log() { local name=$1; shift; "$@" > "$work/logs/$name.log" 2>&1 || { echo "reference_runs: $name failed:"; tail -5 "$work/logs/$name.log"; exit 1; }; }
small=(--set dem.particles.count=200 --set dem.seed=5 --set dem.prepare.cycles=2
       --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3
       --set dem.equilibrium.verify_steps=2000 --set dem.prepare.inertial_number=0.05
       --set dem.prepare.initial_solid_fraction=0.35 --set dem.load.final_strain=0.002
       --set 'dem.load.checkpoint_strains=[0.001, 0.002]' --set dem.load.history_interval=2e-4)
ovoid=(--set dem.particles.aspect_ratio=0.625 --set dem.particles.count=150 --set dem.particles.diameter_min=0.1e-3
       --set dem.particles.d50=0.15e-3 --set dem.particles.diameter_max=0.2e-3 --set dem.prepare.cycles=1
       --set dem.equilibrium.verify_steps=0)

for n in 1 2; do
  out=$work/spheres_np$n
  log "spheres_np${n}_prepare" mpiexec --oversubscribe -n $n "$dem" prepare "${small[@]}" --set dem.output_dir="$out"
  log "spheres_np${n}_load" mpiexec --oversubscribe -n $n "$dem" load "${small[@]}" --set dem.output_dir="$out" \
    --input "$out/prepared.h5"
done

out=$work/ovoids
log ovoids_prepare "$dem" prepare "${small[@]}" "${ovoid[@]}" --set dem.output_dir="$out"
log ovoids_load "$dem" load "${small[@]}" "${ovoid[@]}" --set dem.output_dir="$out" --input "$out/prepared.h5"

# The same ovoids loaded on 2 ranks, and ovoids with the curvature Hertz radius.
out=$work/ovoids_np2
mkdir -p "$out"
cp "$work/ovoids/prepared.h5" "$out/"
log ovoids_np2_load mpiexec --oversubscribe -n 2 "$dem" load "${small[@]}" "${ovoid[@]}" --set dem.output_dir="$out" \
  --input "$out/prepared.h5"
out=$work/curvature
log curvature_prepare "$dem" prepare "${small[@]}" "${ovoid[@]}" --set dem.material.hertz_radius=curvature \
  --set dem.output_dir="$out"
log curvature_load "$dem" load "${small[@]}" "${ovoid[@]}" --set dem.material.hertz_radius=curvature \
  --set dem.output_dir="$out" --input "$out/prepared.h5"

# Global damping during the loading.
out=$work/damped
mkdir -p "$out"
cp "$work/spheres_np1/prepared.h5" "$out/"
log damped_load "$dem" load "${small[@]}" --set dem.integration.global_damping=0.1 --set dem.output_dir="$out" \
  --input "$out/prepared.h5"

# OVAL's loading: relaxed increments, checkpoints as loaded.
out=$work/increments
mkdir -p "$out"
cp "$work/spheres_np1/prepared.h5" "$out/"
increments=(--set dem.load.increment=1e-4 --set dem.load.increment_tolerance=1e-2
            --set dem.equilibrium.at_checkpoints=false)
log increments_load "$dem" load "${small[@]}" "${increments[@]}" --set dem.output_dir="$out" --input "$out/prepared.h5"

# A resume from the first checkpoint must give the second one again.
out=$work/resumed
mkdir -p "$out"
cp "$work/spheres_np1"/{prepared.h5,load_000.h5,history.h5} "$out/"
log resumed_load "$dem" load "${small[@]}" --set dem.output_dir="$out" --input "$out/load_000.h5" --resume

# relax and hold of a loosely relaxed checkpoint, on 2 ranks.
out=$work/relax
mkdir -p "$out"
log relax mpiexec --oversubscribe -n 2 "$dem" relax "${small[@]}" --input "$work/increments/load_001.h5" \
  --output "$out/relaxed.h5"
log hold mpiexec --oversubscribe -n 2 "$dem" hold "${small[@]}" --input "$out/relaxed.h5" --steps 3000 \
  --csv "$out/hold.csv"

# The seven probe forks of the relaxed state.
out=$work/probe
log probe "$probe" run --input "$work/relax/relaxed.h5" --set probe.output_dir="$out" --set probe.hold_steps=400 \
  --set probe.window_steps=200
# A round trip through LAMMPS' data format and a ParaView export.
out=$work/interop
mkdir -p "$out"
log export "$dem" export --input "$work/spheres_np1/load_001.h5" --output "$out/load_001.data" \
  --contacts "$out/load_001.contacts"
log import "$dem" import --input "$out/load_001.data" --contacts "$out/load_001.contacts" --output "$out/imported.h5"
log export_xdmf "$dem" export --input "$work/ovoids/load_001.h5" --format xdmf --output "$out/ovoids.xmf"
echo "reference_runs: wrote $work"
