#!/usr/bin/env bash
# SIGTERM during `aniso-dem prepare`: stopped in its second compaction cycle it keeps the first
# one's seized state (prepare_seized_1_0.h5) and the second's compaction where it stopped
# (prepare_seized_2_0_interrupted.h5) and exits 143 naming the command that continues;
# `--resume` continues that compaction, and stopped inside the consolidation keeps the
# relaxation's state (prepare_consolidated_2_0_interrupted.h5); a second `--resume`, on 2 ranks,
# writes prepared.h5
# with the bits of the uninterrupted 1-rank run and removes the kept files. A fresh prepare
# refuses the folder of a stopped one, and a resume refuses another configuration. The stops
# come from ANISO_TEST_STOP_AT_STEP (common/stop_request.hpp), placed from the uninterrupted
# run's log.
#
# usage: interrupt_prepare.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1
two_cycle_prepare

"$dem" prepare "${settings[@]}" --set dem.output_dir=whole --log-level debug >whole.log 2>&1
steps() { sed -n "s/.*cycle *$1: seized after \([0-9]*\) steps.*/\1/p" whole.log; }
cycle1=$(steps 1) cycle2=$(steps 2)
read -r consolidation from < <(sed -n 's/.*consolidation to p0: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p' whole.log) ||
  { echo "FAIL: no two cycles and a consolidation in the uninterrupted run's log:"; cat whole.log; exit 1; }
[ -n "$cycle1" ] && [ -n "$cycle2" ] || { echo "FAIL: no two cycles in whole.log"; cat whole.log; exit 1; }
ls whole/prepare_*.h5 >/dev/null 2>&1 && { echo "FAIL: the uninterrupted prepare left its pieces"; status=1; }

cut=(prepare "${settings[@]}" --set dem.output_dir=cut)
expect_exit 143 cut_cycle \
  "prepare: stopped on SIGTERM at step [0-9]* in the compaction cycle 2: wrote cut/prepare_seized_2_0_interrupted.h5; kept in cut: prepare_seized_1_0.h5, prepare_seized_2_0_interrupted.h5; continue with the same command and --resume: .* --resume$" \
  env ANISO_TEST_STOP_AT_STEP=$((cycle1 + cycle2 / 2)) "$dem" "${cut[@]}"
[ -f cut/prepared.h5 ] && { echo "FAIL: prepare wrote prepared.h5 though stopped"; status=1; }

expect_exit 2 fresh_refused "continue it with --resume" "$dem" "${cut[@]}"
expect_exit 2 other_config "was made with another configuration" "$dem" "${cut[@]}" \
  --set dem.prepare.agitation_speed=0.5 --resume

expect_exit 143 cut_consolidation \
  "stopped on SIGTERM at step [0-9]* in the consolidation of cycle 2: wrote cut/prepare_consolidated_2_0_interrupted.h5" \
  env ANISO_TEST_STOP_AT_STEP=$((from + consolidation / 2)) "$dem" "${cut[@]}" --resume
grep -q "compaction cycle 2: continued from cut/prepare_seized_2_0_interrupted.h5" cut_consolidation.log ||
  { echo "FAIL: the resume did not continue cycle 2:"; cat cut_consolidation.log; status=1; }

mpiexec --oversubscribe -n 2 "$dem" "${cut[@]}" --resume --log-level warn
expect_same_state "interrupted and resumed prepare" whole/prepared.h5 cut/prepared.h5
ls cut/prepare_*.h5 >/dev/null 2>&1 && { echo "FAIL: the resumed prepare left its pieces:"; ls cut; status=1; }
[ $status = 0 ] && echo "prepare stopped in a cycle and in its consolidation resumed to the bits of the uninterrupted run"
exit $status
