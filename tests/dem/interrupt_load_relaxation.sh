#!/usr/bin/env bash
# SIGTERM inside a relaxation of `aniso-dem load` (the verified relaxation before the last
# checkpoint, dem.equilibrium.at_checkpoints, which at paper size outlasts SLURM's KillWait): the
# run stops at the relaxation's next control update with exit 143 and writes load_interrupted.h5
# (with the relaxation's state in /relaxation), leaving the checkpoint before it intact;
# `--resume` on 2 ranks continues the relaxation and ends with the bits of the uninterrupted
# 1-rank run; so does a quasi-static run stopped inside an increment's minimisation. The stop
# comes from ANISO_TEST_STOP_AT_STEP (common/stop_request.hpp), acted on at the first control
# update from that step on, as a SIGTERM arriving then would be: halfway through the
# relaxation, as the uninterrupted run's debug log places it.
#
# usage: interrupt_load_relaxation.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1
small_relaxing_load
settings+=(--set dem.equilibrium.at_checkpoints=true)
"$dem" prepare "${settings[@]}" --set dem.output_dir=. --log-level warn
"$dem" load "${settings[@]}" --set dem.output_dir=whole --input prepared.h5 --log-level debug >whole.log 2>&1

# Halfway through the relaxation before checkpoint 1.
read -r steps from < <(sed -n 's/.*relaxation before checkpoint 1: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p' whole.log) ||
  { echo "FAIL: no 'relaxation before checkpoint 1: N steps, from step S' in the debug log"; exit 1; }
stop_at=$((from + steps / 2))
expect_exit 143 cut "load: stopped on SIGTERM at strain .*load_interrupted.h5; continue with --input .* --resume" \
  env ANISO_TEST_STOP_AT_STEP=$stop_at "$dem" load "${settings[@]}" --set dem.output_dir=cut --input prepared.h5
[ -f cut/load_001.h5 ] && { echo "FAIL: load_001.h5 written, though its relaxation was stopped"; status=1; }
h5dump -a /relaxation/purpose cut/load_interrupted.h5 | grep -q '"checkpoint"' ||
  { echo "FAIL: load_interrupted.h5 holds no checkpoint relaxation in /relaxation"; status=1; }
first=$(md5sum <cut/load_000.h5)
expect_exit 2 fresh_load_from_a_relaxation "holds a relaxation stopped on SIGTERM: continue that run with --resume" \
  "$dem" load "${settings[@]}" --set dem.output_dir=fresh --input cut/load_interrupted.h5
echo "stopped at step $stop_at, $((stop_at - from)) of the $steps steps of the relaxation before checkpoint 1"

mpiexec --oversubscribe -n 2 "$dem" load "${settings[@]}" --set dem.output_dir=cut --input cut/load_interrupted.h5 \
  --resume --log-level warn
[ "$(md5sum <cut/load_000.h5)" = "$first" ] || { echo "FAIL: load_000.h5 changed"; status=1; }
expect_same_state "interrupted and resumed" whole/load_001.h5 cut/load_001.h5
expect_same_history "interrupted and resumed" whole/history.h5 cut/history.h5

# Quasi-static loading: stopped inside the minimisation of the increment that ends at the
# checkpoint strain, the resume relaxes it, then writes the history row and the checkpoint (with
# its own relaxation) that the schedule had ahead of it.
quasi_static=("${settings[@]}" --set dem.load.final_strain=5e-4 --set 'dem.load.checkpoint_strains=[5e-4]'
              --set dem.load.history_interval=1e-4 --set dem.load.quasi_static=true
              --set dem.load.increment=1e-4 --set dem.load.increment_tolerance=1e-3
              --set dem.equilibrium.method=fire --set dem.equilibrium.margin=0.1)
"$dem" load "${quasi_static[@]}" --set dem.output_dir=qs_whole --input prepared.h5 --log-level debug >qs_whole.log 2>&1
read -r steps from < <(sed -n 's/.*relaxation after the increment to strain 0.0005: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p' qs_whole.log) ||
  { echo "FAIL: no 'relaxation after the increment to strain 0.0005: N steps, from step S' in the debug log"; exit 1; }
stop_at=$((from + steps / 2))
expect_exit 143 qs_cut "load: stopped on SIGTERM at strain 0.0005 " \
  env ANISO_TEST_STOP_AT_STEP=$stop_at "$dem" load "${quasi_static[@]}" --set dem.output_dir=qs_cut --input prepared.h5
h5dump -a /relaxation/purpose qs_cut/load_interrupted.h5 | grep -q '"increment"' ||
  { echo "FAIL: load_interrupted.h5 holds no increment relaxation in /relaxation"; status=1; }
echo "quasi-static: stopped at step $stop_at, $((stop_at - from)) of the $steps steps of the last increment's minimisation"
"$dem" load "${quasi_static[@]}" --set dem.output_dir=qs_cut --input qs_cut/load_interrupted.h5 --resume --log-level warn
expect_same_state quasi-static qs_whole/load_000.h5 qs_cut/load_000.h5
expect_same_history quasi-static qs_whole/history.h5 qs_cut/history.h5
[ $status = 0 ] && echo "resumed inside the relaxations to the bits of the uninterrupted runs"
exit $status
