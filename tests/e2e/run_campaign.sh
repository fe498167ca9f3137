#!/usr/bin/env bash
# End-to-end: the campaign on the e2e config, then checks of what it wrote,
# a resume from a mid-run checkpoint that must reproduce the later checkpoint
# bit for bit, and a rerun that must redo nothing.
#
# usage: run_campaign.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/../tools/cli_lib.sh"
source_dir=$1 build_dir=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
run="$work/run"
make -s -C "$source_dir/workflows" campaign CONFIG=configs/e2e.toml OUT="$run" BIN="$build_dir" 2>&1 |
  tee "$work/campaign.log"

fail() { echo "e2e: FAIL: $*" >&2; exit 1; }
# Every stage's results: a stage the campaign takes for not built would be skipped silently.
# Each stage's files lie in a folder of its own.
for f in dem/prepared.h5 dem/load_000.h5 dem/load_001.h5 dem/load_002.h5 dem/history.h5 dem/history.csv report.md \
         figures/stress_strain.png figures/stress_strain.csv probe/probe_load_000.h5 probe/probe_load_002.h5 \
         voxel/voids_load_000.h5 voxel/voids_load_002.h5 voxel/image_load_002.h5 \
         lbm/permeability_image_load_000.h5 lbm/permeability_image_load_002.h5 fabric/fabric.h5 fabric/fabric_series.h5; do
  [ -s "$run/$f" ] || fail "missing output $f"
done
[ "$(ls "$run")" = "$(printf '%s\n' dem fabric figures lbm logs probe report.md settings voxel)" ] \
  || fail "the run folder holds more than the stage folders, figures, logs, settings and report.md: $(ls "$run")"
# Each stage's settings as it ran with them (the Makefile's stages depend on these, not on the config).
for stage in dem fabric probe voxel lbm; do
  [ -s "$run/settings/$stage.json" ] || fail "missing settings/$stage.json"
done
! grep -q 'campaign: skipping' "$work/campaign.log" || fail "the campaign skipped a stage: $(grep 'skipping' "$work/campaign.log")"
# Each stage run keeps its own log in logs/, and its lines are prefixed with the run's name there
# and in the campaign's output.
for name in prepare load fabric probe_load_002_fork3 probe_collect_load_002 voxel_load_001 lbm_load_002 fabric_series; do
  log=$(ls "$run/logs/$name"*.log 2>/dev/null | head -1)
  [ -s "$log" ] || fail "no log of $name in logs/"
  ! grep -qv "^\[$name" "$log" || fail "a line of $log lacks the prefix [$name]: $(grep -v "^\[$name" "$log" | head -1)"
done
grep -q '^\[load\] .*info load done' "$work/campaign.log" || fail "the campaign's output lacks '[load] ... load done'"
h5dump -H "$run/dem/load_001.h5" > "$work/load_001.header" || fail "h5dump -H cannot read load_001.h5"
grep -q 'schema_version' "$work/load_001.header" || fail "checkpoint header lacks schema_version"
h5dump -H "$run/dem/history.h5" > /dev/null || fail "h5dump -H cannot read history.h5"
/usr/bin/python3 - "$run" <<'PY' || fail "report numbers"
import sys, h5py, numpy as np
run = sys.argv[1]
with h5py.File(f"{run}/dem/history.h5") as f:
    h = {k: f["history"][k][()] for k in f["history"]}
strain = -h["strain_11"]
assert abs(strain[-1] - 0.01) < 1e-3, f"final strain {strain[-1]}"
assert np.all(np.abs(h["strain_22"]) == 0.0), "eps22 must stay exactly 0 in plane strain"
ratio = (h["stress_33"] - h["stress_11"]) / h["p"]
assert ratio.max() > 0.1, f"no deviatoric stress built up: max ratio {ratio.max()}"
assert 0.3 < h["void_ratio"][0] < 1.0, f"implausible void ratio {h['void_ratio'][0]}"
assert np.all(np.abs(h["p"][1:] - 1e5) / 1e5 < 0.2), "mean stress far from 100 kPa"
print(f"e2e: peak ratio {ratio.max():.4f}, e0 {h['void_ratio'][0]:.4f}")
PY

# Resume from checkpoint 1 in a copy: checkpoint 2 must come out identical.
resumed="$work/resumed"
mkdir -p "$resumed"
cp "$run"/dem/{prepared.h5,load_000.h5,load_001.h5,history.h5} "$resumed/"
"$build_dir/dem/aniso-dem" load --config "$source_dir/workflows/configs/e2e.toml" --set dem.output_dir="$resumed" \
  --input "$resumed/load_001.h5" --resume --log-level warn
for group in /particles /contacts /cell; do
  h5diff "$run/dem/load_002.h5" "$resumed/load_002.h5" "$group" "$group" || fail "resumed run differs in $group"
done
h5diff "$run/dem/history.h5" "$resumed/history.h5" /history /history || fail "resumed history differs"

# Kill the whole campaign (SIGKILL, as a lost node would) once the load has
# written its first checkpoint and history, then rerun it: the rerun must
# continue the load from its newest checkpoint, leave every finished file
# untouched and end with exactly the uninterrupted run's results.
killed="$work/killed"
kill_when_written "$killed/dem/history.h5" "$work/killed.log" \
  make -s -C "$source_dir/workflows" campaign CONFIG=configs/e2e.toml OUT="$killed" BIN="$build_dir"
[ ! -e "$killed/dem/load.done" ] || fail "the campaign finished before it was killed; nothing was interrupted"
finished=$(cd "$killed" && ls dem/prepared.h5 dem/load_*.h5)
stamps() { (cd "$killed" && stat -c '%n %Y %i' $finished); }
before=$(stamps)
make -s -C "$source_dir/workflows" campaign CONFIG=configs/e2e.toml OUT="$killed" BIN="$build_dir" \
  >"$work/rerun.log" 2>&1 || fail "the rerun after the kill failed: $(tail -5 "$work/rerun.log")"
grep -q "resuming the interrupted load from $killed/dem/load_00" "$work/rerun.log" \
  || fail "the rerun did not resume the load from a checkpoint: $(grep -i 'load' "$work/rerun.log" | head -3)"
! grep -q 'aniso-dem prepare' "$work/rerun.log" || fail "the rerun redid the preparation"
[ "$before" = "$(stamps)" ] || fail "the rerun rewrote finished files: $before"
"$source_dir/tests/workflows/compare_runs.py" "$run" "$killed" || fail "the killed-and-rerun campaign differs"

# A rerun finds everything up to date.
if make -C "$source_dir/workflows" -q campaign CONFIG=configs/e2e.toml OUT="$run" BIN="$build_dir"; then :; else
  fail "a rerun of the finished campaign would redo work"
fi
echo "e2e: all checks passed"
