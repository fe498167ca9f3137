#!/usr/bin/env bash
# The probe's determinism, through the executable: `run` twice on 1 rank, on 2 and on 6
# ranks, and the seven forks one at a time (`fork`, as a job array would, on 2 ranks)
# followed by `collect`, must all give identical bits in /stiffness and /forks (h5diff,
# exact comparison).
#
# usage: identical_ranks.sh BUILD_DIR CHECKPOINT WORK_DIR
set -euo pipefail
build=$1 checkpoint=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
export OMPI_MCA_mpi_yield_when_idle=1 # ranks above the core count yield instead of spinning
probe=$build/probe/aniso-probe
stem=$(basename "$checkpoint" .h5)
run_on() { # ranks folder
  mpiexec --oversubscribe -n "$1" "$probe" run --input "$checkpoint" --set probe.output_dir="$work/$2" --log-level warn
}
run_on 1 np1
run_on 1 np1_again
run_on 2 np2
run_on 6 np6
for fork in 0 1 2 3 4 5 6; do
  mpiexec --oversubscribe -n 2 "$probe" fork --input "$checkpoint" --fork "$fork" \
    --set probe.output_dir="$work/forks" --log-level warn
done
"$probe" collect --input "$checkpoint" --set probe.output_dir="$work/forks" --log-level warn
status=0
for other in np1_again np2 np6 forks; do
  for group in /stiffness /forks; do
    if ! h5diff "$work/np1/probe_$stem.h5" "$work/$other/probe_$stem.h5" "$group" "$group" > "$work/diff.txt"; then
      echo "FAIL: $other: $group differs from 1 rank:"; head -8 "$work/diff.txt"; status=1
    fi
  done
done
[ $status = 0 ] && echo "identical bits: repeated, 2 and 6 ranks, and seven single forks on 2 ranks + collect"
exit $status
