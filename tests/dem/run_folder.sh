#!/usr/bin/env bash
# Output folders keep one run each: a fresh load refuses a folder that holds another
# loading run unless --overwrite (which never removes its own input); --resume refuses another
# run's history, a prepared assembly, a checkpoint beyond what the history reaches (by its
# covers_step or by its rows) and a history of another schema version (exit 3); a second writer
# is refused while the first holds the folder's lock, which no run leaves behind, failed or not;
# aniso-fabric refuses to write its results over its input. Each refusal: exit 2, a message
# naming the problem, and no file of the earlier run changed.
#
# usage: run_folder.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
cd "$work"
dem=$build/dem/aniso-dem
settings=(--set dem.particles.count=200 --set dem.seed=4 --set dem.prepare.cycles=1
          --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3
          --set dem.prepare.initial_solid_fraction=0.35 --set dem.equilibrium.at_checkpoints=false
          --set dem.load.final_strain=0.004 --set 'dem.load.checkpoint_strains=[0.001, 0.002, 0.004]'
          --set dem.load.history_interval=1e-4 --log-level warn)
"$dem" prepare "${settings[@]}" --set dem.output_dir=prep
"$dem" load "${settings[@]}" --set dem.output_dir=A --input prep/prepared.h5
"$dem" load "${settings[@]}" --set dem.output_dir=B --input prep/prepared.h5
sums_before=$(md5sum A/* B/*)
status=0
for folder in A B prep; do
  if [ -e "$folder/.aniso-dem.lock" ]; then
    echo "FAIL: $folder/.aniso-dem.lock is left behind after the run ended"
    status=1
  fi
done

source "$(dirname "$0")/../tools/cli_lib.sh"
# expect NAME PATTERN COMMAND...: exit 2 with PATTERN in the output.
expect() {
  local name=$1 pattern=$2
  shift 2
  expect_exit 2 "$name" "$pattern" "$@"
}

expect fresh_into_a_run "already holds a loading run" \
  "$dem" load "${settings[@]}" --set dem.output_dir=A --input prep/prepared.h5
expect overwrite_own_input "is a file of the run it would remove" \
  "$dem" load "${settings[@]}" --set dem.output_dir=A --input A/load_001.h5 --overwrite
expect resume_and_overwrite "give one of them" \
  "$dem" load "${settings[@]}" --set dem.output_dir=A --input A/load_001.h5 --resume --overwrite
expect resume_a_prepared_assembly "not a checkpoint of a loading run" \
  "$dem" load "${settings[@]}" --set dem.output_dir=A --input prep/prepared.h5 --resume
expect resume_into_another_run "belongs to loading run" \
  "$dem" load "${settings[@]}" --set dem.output_dir=B --input A/load_001.h5 --resume
expect second_writer "another aniso-dem" \
  flock A/.aniso-dem.lock "$dem" load "${settings[@]}" --set dem.output_dir=A --input A/load_001.h5 --resume
expect fabric_over_its_input "writing it would replace the input" \
  "$build/fabric/aniso-fabric" --input A/load_002.h5 --output ./A/../A/load_002.h5
if [ "$(md5sum A/* B/*)" != "$sums_before" ]; then
  echo "FAIL: a refused command changed a file of run A or B"
  status=1
fi

# A history that stops short of the checkpoint (the run ended before reaching it) is refused.
cp -r A short
"$dem" load "${settings[@]}" --set dem.output_dir=short --input short/load_000.h5 --resume \
  --set dem.load.final_strain=0.0015 --set 'dem.load.checkpoint_strains=[0.001]'
expect resume_beyond_the_history "before the input checkpoint's step" \
  "$dem" load "${settings[@]}" --set dem.output_dir=short --input A/load_002.h5 --resume

# A history whose covers_step claims the checkpoint but whose rows stop short of it (replaced by
# an older copy, or edited) is refused by its rows: accepted, the finished history had a gap.
cp -r A claimed
/usr/bin/python3 - claimed/history.h5 <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    history = f["history"]
    keep = len(history["step"]) // 2
    for name in list(history):
        data, attributes = history[name][:keep], dict(history[name].attrs)
        del history[name]
        history.create_dataset(name, data=data)
        history[name].attrs.update(attributes)
PY
expect resume_past_the_history_rows "rows are missing" \
  "$dem" load "${settings[@]}" --set dem.output_dir=claimed --input claimed/load_002.h5 --resume

# A history of another schema version (another aniso-dem wrote it) is refused by name.
cp -r A old_schema
/usr/bin/python3 - old_schema/history.h5 <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    f.attrs["schema_version"] = np.int64(3)
PY
expect_exit 3 history_of_another_version "schema_version 3, expected 4" \
  "$dem" load "${settings[@]}" --set dem.output_dir=old_schema --input old_schema/load_001.h5 --resume

# The lock is released with its file on every way out: a run that ended (above), and one that failed.
expect_exit 4 prepare_too_few_particles "below twice the interaction range" \
  "$dem" prepare --set dem.particles.count=2 --set dem.output_dir=tiny --log-level warn
if [ -e tiny/.aniso-dem.lock ]; then
  echo "FAIL: a prepare that failed (exit 4) left tiny/.aniso-dem.lock behind"
  status=1
fi

# --overwrite replaces the run: the old files go, a new run id is written.
old_id=$(h5dump -a run_id A/history.h5 | grep -o '"[^"]*"' | tail -1)
"$dem" load "${settings[@]}" --set dem.output_dir=A --input prep/prepared.h5 --overwrite
new_id=$(h5dump -a run_id A/history.h5 | grep -o '"[^"]*"' | tail -1)
checkpoint_id=$(h5dump -a run_id A/load_002.h5 | grep -o '"[^"]*"' | tail -1)
if [ "$old_id" = "$new_id" ] || [ "$checkpoint_id" != "$new_id" ]; then
  echo "FAIL: --overwrite: history run id $old_id -> $new_id, checkpoint $checkpoint_id"
  status=1
fi
[ "$status" = 0 ] && echo "output folders: every refusal exit 2 with its message, no file changed; --overwrite replaced the run; no lock file left behind"
exit "$status"
