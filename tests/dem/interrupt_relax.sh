#!/usr/bin/env bash
# SIGTERM during `aniso-dem relax` and `aniso-dem consolidate` (--input X --output Y): each stops
# at its relaxation's next control update with exit 143, writes Y with _interrupted before .h5
# and names it in its log line, leaving its input as it was; the same command with --resume from
# that file writes Y with the bits of the uninterrupted 1-rank run (relax resumed on 2 ranks). The
# stop comes from ANISO_TEST_STOP_AT_STEP (common/stop_request.hpp), acted on at the first control
# update from that step on: relax is stopped in its verification window, consolidate while
# minimising, where the uninterrupted runs' debug logs place them.
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

# interrupted RANKS COMMAND INPUT LABEL PERCENT SETTINGS...: the whole run, and one stopped
# PERCENT of the way through it and resumed on RANKS ranks, compared.
interrupted() {
  local ranks=$1 command=$2 input=$3 label=$4 percent=$5
  shift 5
  "$dem" "$command" --input "$input" --output "whole/$command.h5" "$@" --log-level debug >"$command-whole.log" 2>&1
  local steps from
  read -r steps from < <(sed -n "s/.*$label: \([0-9]*\) steps, from step \([0-9]*\).*/\1 \2/p" "$command-whole.log") ||
    { echo "FAIL: no '$label: N steps, from step S' in the debug log"; exit 1; }
  local stop_at=$((from + steps * percent / 100))
  local before
  before=$(md5sum <"$input")
  expect_exit 143 "$command-cut" \
    "$command: stopped on SIGTERM at step [0-9]* .*wrote cut/${command}_interrupted.h5; continue with --input cut/${command}_interrupted.h5 --output cut/$command.h5 --resume" \
    env ANISO_TEST_STOP_AT_STEP="$stop_at" "$dem" "$command" --input "$input" --output "cut/$command.h5" "$@"
  [ -f "cut/$command.h5" ] && { echo "FAIL: $command wrote its output though stopped"; status=1; }
  [ "$(md5sum <"$input")" = "$before" ] || { echo "FAIL: $command changed its input"; status=1; }
  echo "$command stopped at step $stop_at, $((stop_at - from)) of its $steps steps"
  mpiexec --oversubscribe -n "$ranks" "$dem" "$command" --input "cut/${command}_interrupted.h5" --output "cut/$command.h5" \
    --resume "$@" --log-level warn
  expect_same_state "$command interrupted and resumed" "whole/$command.h5" "cut/$command.h5"
}
interrupted 2 relax load/load_000.h5 "relax" 90 --set dem.equilibrium.tolerance=1e-3
interrupted 1 consolidate dem/prepared.h5 "consolidation to p0" 2 --set dem.prepare.confining_pressure=150e3

# A fresh run refuses a file stopped mid-relaxation (its control is the relaxation's), and a
# resume refuses a file that is not one.
expect_exit 2 fresh_refused "continue that with --resume" "$dem" relax --input cut/relax_interrupted.h5 \
  --output other/relax.h5
expect_exit 2 resume_refused "holds no interrupted relax" "$dem" relax --input load/load_000.h5 \
  --output other/relax.h5 --resume
[ $status = 0 ] && echo "relax and consolidate resumed to the bits of their uninterrupted runs"
exit $status
