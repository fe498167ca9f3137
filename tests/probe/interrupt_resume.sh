#!/usr/bin/env bash
# SIGTERM to a running `aniso-probe run` (what SLURM sends at a time limit): it stops within 100
# steps of the fork in progress, keeps the forks it finished as fork files, writes no result, names
# what is done and left and the command that continues, and exits 143; the same command then runs
# only the forks left, and its /stiffness and /forks are those of an uninterrupted run to the last
# bit. The signal is sent once the log shows fork 0 finished, so that a fork is in progress.
#
# usage: interrupt_resume.sh BUILD_DIR CHECKPOINT WORK_DIR
set -euo pipefail
build=$1 checkpoint=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
probe=$build/probe/aniso-probe
stem=$(basename "$checkpoint" .h5)
source "$(dirname "$0")/../tools/cli_lib.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }
# Forks of about a second each (200 spheres, 2 x 15000 steps held), so that one is in progress when
# the signal comes. Holds that long outlast the fixture's 2000-step verified window, and the
# increment check may refuse what they read; this test is about the bits of a stop and a resume,
# so it keeps the result either way (the check has its own tests).
run=("$probe" run --input "$checkpoint" --set probe.hold_steps=15000 --set probe.check_increment=false)

"${run[@]}" --set probe.output_dir="$work/whole" --log-level warn

# The interrupted run: SIGTERM as soon as fork 0 is reported done.
stop_when_logged "fork 0 (reference)" "$work/stopped.log" "${run[@]}" --set probe.output_dir="$work/stopped"
code=$stopped_code
cat "$work/stopped.log"
[ "$code" = 143 ] || fail "the stopped run exited $code, expected 143"
grep -q "stopped on SIGTERM: forks done: 0.* (kept as .*probe_${stem}_fork<N>.h5); forks left: .*6; continue with the same command, which runs only the forks left: .*aniso-probe run --input $checkpoint" \
  "$work/stopped.log" || fail "the stop message does not say what is done, what is left and how to continue"
[ ! -e "$work/stopped/probe_$stem.h5" ] || fail "a stopped run wrote a result"
[ -z "$(find "$work/stopped" -name '.*.tmp-*')" ] || fail "a temporary file was left behind"
[ -f "$work/stopped/probe_${stem}_fork0.h5" ] || fail "fork 0 was not kept"
kept=$(ls "$work/stopped" | grep -c "_fork[0-6].h5$")
[ "$kept" -lt 7 ] || fail "all seven forks were kept: the signal came too late to test anything"
# The kept forks hold the uninterrupted run's readings.
for file in "$work"/stopped/probe_"$stem"_fork*.h5; do
  n=${file##*_fork}
  n=${n%.h5}
  for dataset in samples_half samples_final stress_start; do
    h5diff -q "$file" "$work/whole/probe_$stem.h5" "/fork/$dataset" "/forks/fork_$n/$dataset" ||
      fail "$file: /fork/$dataset differs from the uninterrupted run's fork $n"
  done
done

# The same command continues: only the forks left run, and the result is the uninterrupted one.
"${run[@]}" --set probe.output_dir="$work/stopped" > "$work/resumed.log" 2>&1 || { cat "$work/resumed.log"; fail "the resumed run failed"; }
grep -q "forks already done by an earlier run: 0" "$work/resumed.log" ||
  { cat "$work/resumed.log"; fail "the resumed run did not reuse the kept forks"; }
ran=$(grep -c "^.*fork [0-6] (" "$work/resumed.log" || true)
[ "$ran" = $((7 - kept)) ] || { cat "$work/resumed.log"; fail "the resumed run ran $ran forks, expected $((7 - kept))"; }
for group in /stiffness /forks; do
  h5diff "$work/whole/probe_$stem.h5" "$work/stopped/probe_$stem.h5" "$group" "$group" > "$work/diff.txt" ||
    { head -8 "$work/diff.txt"; fail "$group of the resumed run differs from the uninterrupted run"; }
done
[ -z "$(ls "$work/stopped" | grep "_fork[0-6].h5$")" ] || fail "the fork files were not removed after the result"
[ -z "$(find "$work/stopped" -name '.*.tmp-*')" ] || fail "a temporary file was left behind"
echo "interrupt_resume.sh: stopped with $kept of 7 forks kept; the resumed result is the uninterrupted one"
