#!/usr/bin/env bash
# SIGKILL during `aniso-dem load` (a lost node, the end of an allocation or login session): with
# --keep-every 0.001 the loading's state is kept as load_interrupted.h5, with the history after it,
# every 0.06 s. Killed once such a state exists, the run resumes from the point that
# `campaign.py load-input` picks (that file, the history being newer) and ends with the bits of
# the uninterrupted run (the last checkpoint and the history); the finished run removes the file
# it kept. Keeping does not change the run.
#
# usage: kill_load.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
build=$1 work=$2 source_dir=$3
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
python=/usr/bin/python3
small_continuous_load
"$dem" prepare "${settings[@]}" --set dem.output_dir=. --log-level warn
"$dem" load "${settings[@]}" --set dem.output_dir=whole --input prepared.h5 >whole.log 2>&1
grep -q "kept at strain" whole.log && { echo "FAIL: the default clock (20 min) kept a run of seconds"; status=1; }
"$dem" load "${settings[@]}" --set dem.output_dir=kept --input prepared.h5 --keep-every 0.001 >kept.log 2>&1
grep -q "load: kept at strain [0-9.e-]* (step [0-9]*) in kept/load_interrupted.h5" kept.log ||
  { echo "FAIL: --keep-every 0.001 kept nothing:"; tail kept.log; status=1; }
[ -e kept/load_interrupted.h5 ] && { echo "FAIL: the finished run left the state it kept"; status=1; }
expect_same_state "a load keeping its state every 0.06 s" whole/load_001.h5 kept/load_001.h5
expect_same_history "a load keeping its state every 0.06 s" whole/history.h5 kept/history.h5

# A campaign's folder (prepared.h5 beside the load's files) and settings older than the run, as
# campaign.py's settings/dem.json is.
mkdir cut
cp prepared.h5 cut/
touch -d "1 hour ago" dem.json cut/prepared.h5
setsid "$dem" load "${settings[@]}" --set dem.output_dir=cut --input cut/prepared.h5 --keep-every 0.001 >cut.log 2>&1 &
group=$!
until [ -e cut/load_000.h5 ]; do
  kill -0 "$group" 2>/dev/null || { echo "FAIL: the load ended before load_000.h5: $(tail -3 cut.log)"; exit 1; }
  sleep 0.02
done
sleep 0.3 # a few kept states after load_000.h5
kill -KILL -- "-$group"
wait "$group" 2>/dev/null || true
grep -q "load done" cut.log && { echo "FAIL: the load finished before the kill"; exit 1; }
# A kill between a kept state and its history leaves the state uncovered: load-input then takes
# load_000.h5 (a few percent of the runs).
read -r -a resume < <("$python" "$source_dir/workflows/campaign.py" load-input cut dem.json 2>/dev/null)
[ "${resume[1]:-}" = cut/load_interrupted.h5 ] || [ "${resume[1]:-}" = cut/load_000.h5 ] ||
  { echo "FAIL: load-input picked '${resume[*]}', expected cut/load_interrupted.h5 or cut/load_000.h5"; status=1; }
[ -e cut/load_interrupted.h5 ] || { echo "FAIL: the killed run kept no state:"; ls cut; status=1; }
"$dem" load "${settings[@]}" --set dem.output_dir=cut "${resume[@]}" --keep-every 0.001 >resumed.log 2>&1 ||
  { echo "FAIL: the resume failed:"; tail resumed.log; exit 1; }
expect_same_state "a load killed and resumed from what it kept" whole/load_001.h5 cut/load_001.h5
expect_same_history "a load killed and resumed from what it kept" whole/history.h5 cut/history.h5
[ -e cut/load_interrupted.h5 ] && { echo "FAIL: the finished resume left the state it kept"; status=1; }
expect_exit 2 negative "--keep-every: expected minutes, 0 or more" "$dem" load "${settings[@]}" \
  --set dem.output_dir=negative --input prepared.h5 --keep-every -0.5
[ $status = 0 ] && echo "a load killed after keeping its state resumed from ${resume[1]} to the bits of the uninterrupted run"
exit $status
