#!/usr/bin/env bash
# dem.equilibrium.fork_checkpoints: each checkpoint is a relaxed copy of the loading state, and
# the loading goes on from the state itself. Checked on 200 spheres loaded to 0.4%:
# - the loading's history is that of a run without relaxations (at_checkpoints = false), to the bit;
# - each checkpoint is the state `aniso-dem relax` makes of that run's checkpoint, to the bit, and
#   it holds p within 1e-3 over a 2000-step fixed-cell hold where the unrelaxed one does not;
# - SIGTERM while a copy relaxes: exit 143, load_interrupted.h5 holds the loading's state (purpose
#   checkpoint_fork), the checkpoint before it intact; --resume on 2 ranks gives the bits of the
#   uninterrupted run; a resume without fork_checkpoints is refused (exit 2, naming the key);
# - a copy out of its step budget: exit 5 naming the kept loading state, resumed to the same bits;
# - load_resume.h5 holds the loading's own state at the newest checkpoint (that of the run without
#   relaxations, to the bit); a run killed after checkpoint 0 resumes from it to the same bits,
#   and --resume from a copy is refused (exit 2, naming load_resume.h5).
#
# usage: fork_checkpoints.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
dem=$1/dem/aniso-dem
enter_fresh_folder "$2"
export OMPI_MCA_mpi_yield_when_idle=1
small_relaxing_load
fork=("${settings[@]}" --set dem.equilibrium.at_checkpoints=true --set dem.equilibrium.fork_checkpoints=true)
"$dem" prepare "${settings[@]}" --set dem.output_dir=. --log-level warn
"$dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false --set dem.output_dir=plain \
  --input prepared.h5 --log-level warn
"$dem" load "${fork[@]}" --set dem.output_dir=whole --input prepared.h5 --log-level debug >whole.log 2>&1

expect_same_history "forked checkpoints against none relaxed" plain/history.h5 whole/history.h5
expect_same_state "load_resume.h5 against the unrelaxed run's last checkpoint" plain/load_001.h5 whole/load_resume.h5
expect_exit 2 resume_copy "is a relaxed copy of the loading's state .* resume from load_resume.h5" \
  "$dem" load "${fork[@]}" --set dem.output_dir=whole --input whole/load_000.h5 --resume
for k in 000 001; do
  "$dem" relax "${settings[@]}" --input plain/load_$k.h5 --output relaxed_$k.h5 --log-level warn
  expect_same_state "checkpoint $k: the fork against relax of the unrelaxed run's" relaxed_$k.h5 whole/load_$k.h5
done
expect_exit 5 hold_plain "above --max-drift" "$dem" hold --input plain/load_001.h5 --steps 2000 --max-drift 1e-3
expect_exit 0 hold_fork "hold of" "$dem" hold --input whole/load_001.h5 --steps 2000 --max-drift 1e-3

# Halfway through the relaxation of checkpoint 1's copy.
read -r steps from < <(sed -n "s/.*relaxation of checkpoint 1's copy: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p" whole.log) ||
  { echo "FAIL: no \"relaxation of checkpoint 1's copy: N steps, from step S\" in the debug log"; exit 1; }
stop_at=$((from + steps / 2))
expect_exit 143 cut "load: stopped on SIGTERM at strain .*load_interrupted.h5; continue with --input .* --resume" \
  env ANISO_TEST_STOP_AT_STEP=$stop_at "$dem" load "${fork[@]}" --set dem.output_dir=cut --input prepared.h5
[ -f cut/load_001.h5 ] && { echo "FAIL: load_001.h5 written, though its relaxation was stopped"; status=1; }
h5dump -a /relaxation/purpose cut/load_interrupted.h5 | grep -q '"checkpoint_fork"' ||
  { echo "FAIL: load_interrupted.h5 holds no checkpoint_fork in /relaxation"; status=1; }
step=$(h5dump -a /step cut/load_interrupted.h5 | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
[ "$step" = "$from" ] || { echo "FAIL: load_interrupted.h5 is at step '$step', not the loading's $from"; status=1; }
first=$(md5sum <cut/load_000.h5)
expect_exit 2 resume_unforked "fork_checkpoints = true; resume it with the same setting" \
  "$dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=true --set dem.output_dir=cut \
  --input cut/load_interrupted.h5 --resume
echo "stopped at step $stop_at, $((stop_at - from)) of the $steps steps relaxing checkpoint 1's copy"
# As if killed (SIGKILL) then: no load_interrupted.h5, the resume point is load_resume.h5 of checkpoint 0.
cp -r cut killed && rm killed/load_interrupted.h5
"$dem" load "${fork[@]}" --set dem.output_dir=killed --input killed/load_resume.h5 --resume --log-level warn
expect_same_state "killed after checkpoint 0, resumed from load_resume.h5" whole/load_001.h5 killed/load_001.h5
expect_same_history "killed after checkpoint 0, resumed from load_resume.h5" whole/history.h5 killed/history.h5
mpiexec --oversubscribe -n 2 "$dem" load "${fork[@]}" --set dem.output_dir=cut --input cut/load_interrupted.h5 \
  --resume --log-level warn
[ "$(md5sum <cut/load_000.h5)" = "$first" ] || { echo "FAIL: load_000.h5 changed"; status=1; }
expect_same_state "interrupted and resumed" whole/load_001.h5 cut/load_001.h5
expect_same_history "interrupted and resumed" whole/history.h5 cut/history.h5
# The step budget ends checkpoint 0's copy: exit 5, and the loading's state is kept in
# load_interrupted.h5 with its history; --resume with the budget relaxes a new copy, to the same bits.
expect_exit 5 budget "load_interrupted.h5: --resume it with a larger dem.equilibrium.max_steps" \
  "$dem" load "${fork[@]}" --set dem.equilibrium.max_steps=500 --set dem.output_dir=budget --input prepared.h5
h5dump -a /relaxation/purpose budget/load_interrupted.h5 | grep -q '"checkpoint_fork"' ||
  { echo "FAIL: the budget's load_interrupted.h5 holds no checkpoint_fork in /relaxation"; status=1; }
"$dem" load "${fork[@]}" --set dem.output_dir=budget --input budget/load_interrupted.h5 --resume --log-level warn
for k in 000 001; do expect_same_state "out of budget, then resumed" whole/load_$k.h5 budget/load_$k.h5; done
expect_same_history "out of budget, then resumed" whole/history.h5 budget/history.h5
[ $status = 0 ] && echo "forked checkpoints: the unrelaxed path, relaxed copies, resumed to the same bits"
exit $status
