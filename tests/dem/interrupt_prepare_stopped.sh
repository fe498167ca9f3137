#!/usr/bin/env bash
# A frictionless-made assembly (dem.prepare.compaction_stop_void_ratio) stopped on SIGTERM in its
# compaction: the resume, on 2 ranks, runs the consolidation and the corrections (the stop moved by
# the consolidation's miss, the compaction run again from the sparse start) and writes prepared.h5
# with the bits of the uninterrupted 1-rank run. The target is placed from a run without corrections so that at least one runs; the
# stop comes from ANISO_TEST_STOP_AT_STEP, placed from the uninterrupted run's log.
#
# usage: interrupt_prepare_stopped.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1
settings=(--set dem.particles.count=200 --set dem.seed=3 --set dem.material.friction_prepare=0
  --set dem.prepare.compaction_stop_void_ratio=0.62 --set dem.equilibrium.tolerance=1e-3
  --set dem.prepare.initial_solid_fraction=0.35 --set dem.prepare.void_ratio_tolerance=0.008)

"$dem" prepare "${settings[@]}" --set dem.prepare.refinement_cycles=0 --set dem.prepare.void_ratio_tolerance=1 \
  --set dem.output_dir=first >first.log 2>&1
first_e=$(sed -n 's/.*wrote first\/prepared.h5: e = \([0-9.]*\),.*/\1/p' first.log)
[ -n "$first_e" ] || { echo "FAIL: no prepared e in first.log:"; cat first.log; exit 1; }
# A target 0.01 looser than the stop gave: corrections move the stop by the miss.
target=$(awk -v e="$first_e" 'BEGIN { printf "%.4f", e + 0.01 }')
settings+=(--set dem.prepare.target_void_ratio="$target" --set dem.prepare.refinement_cycles=3)

"$dem" prepare "${settings[@]}" --set dem.output_dir=whole --log-level debug >whole.log 2>&1 ||
  { echo "FAIL: the corrected prepare failed:"; cat whole.log; exit 1; }
grep -q "correction 1: stopped after" whole.log || { echo "FAIL: no correction in whole.log"; cat whole.log; exit 1; }
cycle1=$(sed -n 's/.*cycle *1: seized after \([0-9]*\) steps.*/\1/p' whole.log)
[ -n "$cycle1" ] || { echo "FAIL: no compaction steps in whole.log"; cat whole.log; exit 1; }

# Each correction compacts again from the sparse start (step 0), so a stop by step number lands in
# the first compaction; the resumed run then goes through the consolidation and the correction.
cut=(prepare "${settings[@]}" --set dem.output_dir=cut)
expect_exit 143 cut_compaction "in the compaction cycle 1: wrote cut/prepare_seized_1_0_interrupted.h5" \
  env ANISO_TEST_STOP_AT_STEP=$((cycle1 / 2)) "$dem" "${cut[@]}"
mpiexec --oversubscribe -n 2 "$dem" "${cut[@]}" --resume --log-level warn
expect_same_state "frictionless-made prepare interrupted and resumed on 2 ranks" whole/prepared.h5 cut/prepared.h5
[ $status = 0 ] && echo "a frictionless-made prepare with a correction, interrupted and resumed on 2 ranks, gave the bits of the uninterrupted run"
exit $status
