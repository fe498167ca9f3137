#!/usr/bin/env bash
# SIGTERM during `aniso-dem load` (what SLURM sends at a time limit and on scancel): the run
# stops at its next control update with exit 143 and writes load_interrupted.h5, leaving the
# checkpoints it wrote before intact; `--resume` from that file ends exactly where an
# uninterrupted run ends (particles, contacts and the history, to the bit).
#
# usage: interrupt_resume.sh BUILD_DIR WORK_DIR [--set key=value ...]
#   further arguments are extra settings (another damping, say).
set -euo pipefail
build=$1 work=$2
shift 2
rm -rf "$work"
mkdir -p "$work/whole" "$work/cut"
source "$(dirname "$0")/../tools/cli_lib.sh"
small_continuous_load "$@"
dem=$build/dem/aniso-dem
"$dem" prepare "${settings[@]}" --set dem.output_dir="$work" --log-level warn
"$dem" load "${settings[@]}" --set dem.output_dir="$work/whole" --input "$work/prepared.h5" --log-level warn

# The same run, sent SIGTERM once it has written its first checkpoint.
"$dem" load "${settings[@]}" --set dem.output_dir="$work/cut" --input "$work/prepared.h5" >"$work/cut.log" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -f "$work/cut/load_000.h5" ] && break
  sleep 0.05
done
first=$(md5sum <"$work/cut/load_000.h5")
kill -TERM "$pid"
set +e
wait "$pid"
code=$?
set -e
status=0
if [ "$code" != 143 ]; then
  echo "FAIL: the interrupted load ended with exit $code, expected 143 (0: it finished before the signal)"
  cat "$work/cut.log"
  exit 1
fi
grep -q "stopped on SIGTERM at strain .*load_interrupted.h5; continue with --input .* --resume" "$work/cut.log" ||
  { echo "FAIL: no stop message in the log"; status=1; }
[ "$(md5sum <"$work/cut/load_000.h5")" = "$first" ] || { echo "FAIL: load_000.h5 changed"; status=1; }
echo "interrupted: $(grep -o 'stopped on SIGTERM at strain [0-9.e+-]*' "$work/cut.log")"

"$dem" load "${settings[@]}" --set dem.output_dir="$work/cut" --input "$work/cut/load_interrupted.h5" --resume \
  --log-level warn
for dataset in /particles/position /particles/velocity /particles/angular_velocity /contacts/force \
               /contacts/tangential_force; do
  if ! h5diff "$work/whole/load_001.h5" "$work/cut/load_001.h5" "$dataset" "$dataset" >/dev/null; then
    echo "FAIL: $dataset of load_001.h5 differs between the whole and the interrupted-and-resumed run"
    status=1
  fi
done
for column in strain_11 stress_11 stress_33 void_ratio; do
  if ! h5diff "$work/whole/history.h5" "$work/cut/history.h5" "/history/$column" "/history/$column" >/dev/null; then
    echo "FAIL: history column $column differs"
    status=1
  fi
done
[ $status = 0 ] && echo "resumed from load_interrupted.h5 to the same bits as the uninterrupted run"
exit $status
