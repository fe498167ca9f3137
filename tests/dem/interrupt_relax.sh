#!/usr/bin/env bash
# SIGTERM during `aniso-dem relax` and `aniso-dem consolidate` (--input X --output Y): each stops
# at its relaxation's next control update with exit 143, writes Y with _interrupted before .h5
# and names it in its log line, leaving its input as it was; the same command with --resume from
# that file writes Y with the bits of the uninterrupted 1-rank run (relax resumed on 2 ranks). The
# stop comes from ANISO_TEST_STOP_AT_STEP (common/stop_request.hpp), acted on at the first control
# update from that step on: relax is stopped in its verification window, consolidate while
# minimising and relax with dem.equilibrium.kinetic_growth in the escape after a window it left,
# where the uninterrupted runs' debug logs place them. Killed with SIGKILL instead, relax resumes
# from the state it kept (--keep-every).
#
# usage: interrupt_relax.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1
small_prepared_assembly "$build" dem
"$dem" load --input dem/prepared.h5 --set dem.output_dir=load --set dem.particles.count=200 \
  --set dem.load.final_strain=0.01 --set 'dem.load.checkpoint_strains=[0.01]' \
  --set dem.equilibrium.at_checkpoints=false --set dem.load.increment=1e-3 --log-level warn

# interrupted RANKS COMMAND INPUT LABEL WHERE SETTINGS...: the whole run, and one stopped at WHERE
# (a percentage of its steps, or 'escape': halfway through its first escape after a window left on
# its kinetic energy) and resumed on RANKS ranks, compared. NAME (default COMMAND) names the files.
interrupted() {
  local ranks=$1 command=$2 input=$3 label=$4 where=$5
  shift 5
  local name=${NAME:-$command}
  "$dem" "$command" --input "$input" --output "whole/$name.h5" "$@" --log-level debug >"$name-whole.log" 2>&1
  local steps from stop_at
  read -r steps from < <(sed -n "s/.*$label: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p" "$name-whole.log") ||
    { echo "FAIL: no '$label: N steps, from step S' in the debug log"; exit 1; }
  if [ "$where" = escape ]; then
    local escape_steps escape_from
    read -r escape_steps escape_from < <(sed -n "s/.*$label: escaping for \([0-9]*\) steps from step \([0-9]*\).*/\1 \2/p" \
      "$name-whole.log" | head -1) || { echo "FAIL: no escape in the debug log of $name"; exit 1; }
    stop_at=$((escape_from + escape_steps / 2))
  else
    stop_at=$((from + steps * where / 100))
  fi
  local before
  before=$(md5sum <"$input")
  expect_exit 143 "$name-cut" \
    "$command: stopped on SIGTERM at step [0-9]* .*wrote cut/${name}_interrupted.h5; continue with --input cut/${name}_interrupted.h5 --output cut/$name.h5 --resume" \
    env ANISO_TEST_STOP_AT_STEP="$stop_at" "$dem" "$command" --input "$input" --output "cut/$name.h5" "$@"
  [ -f "cut/$name.h5" ] && { echo "FAIL: $command wrote its output though stopped"; status=1; }
  [ "$(md5sum <"$input")" = "$before" ] || { echo "FAIL: $command changed its input"; status=1; }
  echo "$name stopped at step $stop_at, $((stop_at - from)) of its $steps steps"
  mpiexec --oversubscribe -n "$ranks" "$dem" "$command" --input "cut/${name}_interrupted.h5" --output "cut/$name.h5" \
    --resume "$@" --log-level warn
  expect_same_state "$name interrupted and resumed" "whole/$name.h5" "cut/$name.h5"
}
interrupted 2 relax load/load_000.h5 "relax" 90 --set dem.equilibrium.tolerance=1e-3
interrupted 1 consolidate dem/prepared.h5 "consolidation to p0" 2 --set dem.prepare.confining_pressure=150e3
# With the kinetic-growth check (2 here, so that this small state leaves windows on it), stopped
# inside the escape that follows such a window: the file holds stage 'escaping' and how far it got.
NAME=relax_kinetic interrupted 1 relax load/load_000.h5 "relax" escape --set dem.equilibrium.tolerance=1e-3 \
  --set dem.equilibrium.kinetic_growth=2
h5dump -a /relaxation/stage cut/relax_kinetic_interrupted.h5 | grep -q '"escaping"' ||
  { echo "FAIL: the file stopped in the escape does not say so (/relaxation stage)"; status=1; }

# Killed outright (SIGKILL) once it has kept its state (--keep-every 0.001: every 0.06 s), relax
# resumes from the file it kept to the same bits; a run that kept and finished removes that file.
relaxing=(--input load/load_000.h5 --set dem.equilibrium.tolerance=1e-3 --keep-every 0.001)
"$dem" relax "${relaxing[@]}" --output kept/relax.h5 >relax-kept.log 2>&1
grep -q "relax: kept at step [0-9]* ([0-9]* steps relaxed) in kept/relax_interrupted.h5" relax-kept.log ||
  { echo "FAIL: relax --keep-every 0.001 kept nothing:"; tail relax-kept.log; status=1; }
[ -e kept/relax_interrupted.h5 ] && { echo "FAIL: the finished relax left the state it kept"; status=1; }
expect_same_state "relax keeping its state" whole/relax.h5 kept/relax.h5
kill_when_written killed/relax_interrupted.h5 relax-killed.log "$dem" relax "${relaxing[@]}" --output killed/relax.h5
"$dem" relax --input killed/relax_interrupted.h5 --output killed/relax.h5 --resume \
  --set dem.equilibrium.tolerance=1e-3 --log-level warn
expect_same_state "relax killed and resumed from what it kept" whole/relax.h5 killed/relax.h5

# A fresh run refuses a file stopped mid-relaxation (its control is the relaxation's), and a
# resume refuses a file that is not one.
expect_exit 2 fresh_refused "continue that with --resume" "$dem" relax --input cut/relax_interrupted.h5 \
  --output other/relax.h5
expect_exit 2 resume_refused "holds no interrupted relax" "$dem" relax --input load/load_000.h5 \
  --output other/relax.h5 --resume
[ $status = 0 ] && echo "relax and consolidate resumed to the bits of their uninterrupted runs"
exit $status
