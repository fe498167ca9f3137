#!/usr/bin/env bash
# SIGKILL during `aniso-dem prepare` (a lost node, the end of an allocation or login session):
# nothing is asked to stop, so only what the keep clock kept survives. With --keep-every 0.001 the
# compaction or consolidation in progress is kept every 0.06 s (dozens of times in this 3 s
# prepare; 0, every control update, writes 24,000 files in 7 minutes); killed in cycle 2's
# compaction and then in its consolidation, `--resume` (the second on 2 ranks) continues from the
# kept state to the bits of the uninterrupted 1-rank run. Keeping does not change the run: a
# prepare keeping that often writes the same prepared.h5. A kept cycle's piece replaces its
# state in progress. --keep-every below 0 is refused by name.
#
# usage: kill_prepare.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1
two_cycle_prepare

"$dem" prepare "${settings[@]}" --set dem.output_dir=whole >whole.log 2>&1
grep -q "kept at step" whole.log && { echo "FAIL: the default clock (20 min) kept a run of seconds:"; cat whole.log; status=1; }

"$dem" prepare "${settings[@]}" --set dem.output_dir=kept --keep-every 0.001 >kept.log 2>&1
for what in "compaction cycle 1" "compaction cycle 2" "consolidation of cycle 2"; do
  grep -q "$what: kept at step [0-9]* in kept/prepare_.*_interrupted.h5" kept.log ||
    { echo "FAIL: --keep-every 0.001 did not keep the $what:"; tail -20 kept.log; status=1; }
done
expect_same_state "a prepare keeping at every control update" whole/prepared.h5 kept/prepared.h5
ls kept/prepare_*.h5 >/dev/null 2>&1 && { echo "FAIL: the finished prepare left its pieces:"; ls kept; status=1; }

cut=(prepare "${settings[@]}" --set dem.output_dir=cut)
kill_when_written cut/prepare_seized_2_0_interrupted.h5 cut_cycle.log "$dem" "${cut[@]}" --keep-every 0.001
[ -f cut/prepare_seized_1_0.h5 ] || { echo "FAIL: cycle 1's piece was not kept:"; ls cut; status=1; }
[ -f cut/prepare_seized_1_0_interrupted.h5 ] &&
  { echo "FAIL: cycle 1's state in progress outlived its piece:"; ls cut; status=1; }

kill_when_written cut/prepare_consolidated_2_0_interrupted.h5 cut_consolidation.log \
  "$dem" "${cut[@]}" --keep-every 0.001 --resume
grep -q "compaction cycle 2: continued from cut/prepare_seized_2_0_interrupted.h5" cut_consolidation.log ||
  { echo "FAIL: the resume did not continue cycle 2 from what was kept:"; cat cut_consolidation.log; status=1; }

mpiexec --oversubscribe -n 2 "$dem" "${cut[@]}" --resume >resumed.log 2>&1
grep -q "consolidating cycle 2 .*continued from cut/prepare_consolidated_2_0_interrupted.h5" resumed.log ||
  { echo "FAIL: the resume did not continue the consolidation from what was kept:"; cat resumed.log; status=1; }
expect_same_state "prepare killed twice and resumed on 2 ranks" whole/prepared.h5 cut/prepared.h5

expect_exit 2 negative "--keep-every: expected minutes, 0 or more" "$dem" prepare "${settings[@]}" --set dem.output_dir=negative --keep-every -1
[ $status = 0 ] && echo "prepare killed in a cycle and in its consolidation resumed from what it kept to the bits of the uninterrupted run"
exit $status
