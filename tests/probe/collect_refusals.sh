#!/usr/bin/env bash
# collect through the executable: it refuses a missing fork and forks of another checkpoint
# with a file error (exit 3) naming the problem, and leaves no result behind.
#
# usage: collect_refusals.sh BUILD_DIR CHECKPOINT OTHER_CHECKPOINT WORK_DIR
set -uo pipefail
build=$1 checkpoint=$2 other=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
probe=$build/probe/aniso-probe
stem=$(basename "$checkpoint" .h5)
fail() { echo "FAIL: $*"; exit 1; }
expect() { # code pattern command...
  local code=$1 pattern=$2; shift 2
  "$@" > "$work/out.txt" 2>&1
  local got=$?
  [ "$got" = "$code" ] || { cat "$work/out.txt"; fail "exit $got, expected $code: $*"; }
  grep -q -- "$pattern" "$work/out.txt" || { cat "$work/out.txt"; fail "no '$pattern' in the output of: $*"; }
}
for fork in 0 1 2 3 4 5 6; do
  "$probe" fork --input "$checkpoint" --fork "$fork" --set probe.output_dir="$work" --log-level warn ||
    fail "fork $fork failed"
done
"$probe" fork --input "$other" --fork 3 --set probe.output_dir="$work/other" --log-level warn ||
  fail "fork of the other checkpoint failed"
mv "$work/probe_${stem}_fork5.h5" "$work/fork5.h5"
expect 3 "fork 5 is missing" "$probe" collect --input "$checkpoint" --set probe.output_dir="$work"
expect 3 "fork 5 is missing" "$probe" collect --input "$checkpoint" --set probe.output_dir="$work" \
  --forks "$work"/probe_"${stem}"_fork[0-4].h5 "$work/probe_${stem}_fork6.h5"
expect 3 "does not exist" "$probe" collect --input "$checkpoint" --set probe.output_dir="$work" \
  --forks "$work/probe_${stem}_fork0.h5" "$work/nothing.h5"
mv "$work/fork5.h5" "$work/probe_${stem}_fork5.h5"
cp "$work/probe_${stem}_fork3.h5" "$work/fork3.h5"
cp "$work/other/probe_$(basename "$other" .h5)_fork3.h5" "$work/probe_${stem}_fork3.h5"
expect 3 "comes from another checkpoint" "$probe" collect --input "$checkpoint" --set probe.output_dir="$work"
[ -e "$work/probe_$stem.h5" ] && fail "a refused collect wrote $work/probe_$stem.h5"
expect 2 "fork" "$probe" fork --input "$checkpoint" --fork 7 --set probe.output_dir="$work"
mv "$work/fork3.h5" "$work/probe_${stem}_fork3.h5"
expect 0 "wrote" "$probe" collect --input "$checkpoint" --set probe.output_dir="$work"
echo "collect refuses a missing fork and a fork of another checkpoint, and accepts the right seven"
