#!/usr/bin/env bash
# End-to-end: `make paper` on two tiny shapes (tests/e2e/paper/: the paper configs' protocol at a
# few hundred particles, three checkpoints). Checks that it runs every stage of both shapes, draws
# every figure family and fills the comparison's numbers from the runs; that a paper campaign
# killed (SIGKILL) during its first load resumes on a rerun without preparing again and ends with
# the uninterrupted campaign's results bit for bit; that `make paper-export` copies the small results
# (history, fabric, probes, static states, voids, stage times, comparison and figures); that
# `make paper-status` counts every step of the finished study as written; that
# `make paper-export-partial` exports what a killed study finished; that a rerun
# finds everything up to date; and
# that a bad REALISATIONS or a shape without a config is refused before anything runs.
#
# usage: paper_campaign.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/../tools/cli_lib.sh"
source_dir=$1 build_dir=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
fail() { echo "paper e2e: FAIL: $*" >&2; exit 1; }
paper() {
  make -s -C "$source_dir/workflows" "$@" BIN="$build_dir" PAPER_CONFIGS="$source_dir/tests/e2e/paper" \
    PAPER_SHAPES="spheres ovoids-0.5"
}

reference="$work/reference"
paper paper PAPER_OUT="$reference" >"$work/reference.log" 2>&1 || fail "make paper failed: $(tail -5 "$work/reference.log")"
for shape in spheres ovoids-0.5; do
  for f in report.md dem/load_002.h5 fabric/fabric_series.csv probe/probe_load_002.csv voxel/voids_load_002.h5 \
           lbm/permeability_image_load_002.h5; do
    [ -s "$reference/$shape/r1/$f" ] || fail "missing $shape/r1/$f"
  done
  cmp -s "$source_dir/tests/e2e/paper/paper-$shape.toml" "$reference/configs/$shape-r1.toml" \
    || fail "realisation 1's config of $shape is not the shipped config"
done
for f in fig3 shapes_stress_strain fabric_particles fabric_contacts fabric_stress fabric_voids_dem stiffness_C123 \
         stiffness_A voids_distributions voids_anisotropy voids_permeability; do
  [ -s "$reference/figures/$f.png" ] || fail "missing figure $f.png"
done
/usr/bin/python3 - "$reference" <<'PY' || fail "the comparison's numbers"
import csv, re, sys
import h5py
out = sys.argv[1]
text = open(f"{out}/comparison.md").read()
assert "Not drawn" not in text, "a figure family was left out"
with open(f"{out}/figures/signatures.csv") as f:
    rows = {r["shape"]: r for r in csv.DictReader(f)}
assert set(rows) == {"spheres", "alpha = 0.5"}, rows.keys()
for shape, r in rows.items():
    peak, strain = float(r["peak"]), float(r["peak_strain"])
    assert 0.3 < peak < 3 and 0 < strain <= 0.01 + 1e-9, (shape, peak, strain)
    # The cell's x1/x3 at the end from the prepared cell's L1/L3 (1.5 as made, moved a little by
    # the consolidation's servo) and the history's last strains.
    run = f"{out}/{'spheres' if shape == 'spheres' else 'ovoids-0.5'}/r1/dem"
    with h5py.File(f"{run}/prepared.h5") as f:
        lengths = f["cell/lengths"][()]
    with h5py.File(f"{run}/history.h5") as f:
        e11, e33 = f["history/strain_11"][-1], f["history/strain_33"][-1]
    assert abs(lengths[0] / lengths[2] - 1.5) < 0.01, lengths
    expected = lengths[0] / lengths[2] * (1 + e11) / (1 + e33)
    assert abs(float(r["x1_over_x3"]) - expected) < 1e-9 * expected, (r, expected)
    # The table shows the CSV's numbers.
    assert re.search(rf"\| {re.escape(shape)} \| {peak:.3f} \(", text), shape
for heading in ("Table 2", "Figs. C123 and A", "Voids (section 3.4)"):
    assert f"## {heading}" in text, heading
print("paper e2e: comparison filled for", ", ".join(rows))
PY

# make paper-status on the finished study: every kind of step of both runs has all its files.
paper paper-status PAPER_OUT="$reference" >"$work/status.log" 2>"$work/status.err" \
  || fail "make paper-status failed: $(tail -5 "$work/status.err")"
[ "$(grep -c '^  report  *1/1$' "$work/status.log")" = 2 ] || fail "paper-status: not two finished runs: $(cat "$work/status.log")"
[ "$(grep -c '^  load  *1/1 (3 of 3 checkpoints written)$' "$work/status.log")" = 2 ] \
  || fail "paper-status: the loads' checkpoints: $(cat "$work/status.log")"
awk '$2 ~ /^[0-9]+\/[0-9]+$/ { split($2, n, "/"); if (n[1] != n[2]) missing = 1 } END { exit missing }' "$work/status.log" \
  || fail "paper-status counts a step without its files in a finished study: $(cat "$work/status.log")"

# The export of the small results where the docs keep them (make paper-export).
export="$work/export"
paper paper-export PAPER_OUT="$reference" PAPER_EXPORT="$export" >"$work/export.log" 2>&1 \
  || fail "make paper-export failed: $(tail -5 "$work/export.log")"
for shape in spheres ovoids-0.5; do
  for f in history.csv fabric_series.csv fabric_series_correlations.csv probes.csv static_states.csv voids.csv \
           void_curves.csv permeability.csv prepare.log stage_times.csv; do
    [ -s "$export/$shape/$f" ] || fail "paper-export wrote no $shape/$f"
  done
  cmp -s "$reference/$shape/r1/dem/history.csv" "$export/$shape/history.csv" || fail "exported history of $shape differs"
done
cmp -s "$reference/comparison.md" "$export/comparison.md" || fail "exported comparison.md differs"
[ -s "$export/figures/fig3.png" ] || fail "paper-export copied no figures"
/usr/bin/python3 - "$reference" "$export" <<'PY' || fail "the exported tables"
import csv, sys
import h5py
out, export = sys.argv[1:]
for shape in ("spheres", "ovoids-0.5"):
    probes = list(csv.DictReader(open(f"{export}/{shape}/probes.csv")))
    assert [r["source"][-11:-3] for r in probes] == ["load_000", "load_001", "load_002"], probes
    states = list(csv.DictReader(open(f"{export}/{shape}/static_states.csv")))
    assert len(states) == 3, states
    for row in states:
        with h5py.File(f"{out}/{shape}/r1/dem/{row['checkpoint']}.h5") as f:
            a = f.attrs
            assert int(row["relaxation_steps"]) == int(a["step"]) - int(a["relaxed_copy_of_step"]), row
            assert int(row["static_verified"]) == int(a["static_verified"]), row
    rows = list(csv.DictReader(open(f"{export}/{shape}/stage_times.csv")))
    stages = {r["stage"]: float(r["wall_seconds"]) for r in rows}
    assert {"prepare", "load"} <= set(stages) and all(t >= 0 for t in stages.values()), stages
    # every program logs its wall time: the fabric, voxel and LBM stages too, not only DEM and probes
    for prefix in ("fabric", "probe_load_", "voxel_load_", "lbm_load_"):
        timed = [r for r in rows if r["stage"].startswith(prefix) and r["source"] == "timing"]
        assert timed, (prefix, rows)
print("paper e2e: export checked")
PY

# Killed during the first shape's load, once its first checkpoint (a relaxed copy) has left its
# resume point, load_resume.h5 (the loading's own state), then rerun.
killed="$work/killed"
kill_when_written "$killed/spheres/r1/dem/load_resume.h5" "$work/killed.log" \
  make -s -C "$source_dir/workflows" paper BIN="$build_dir" PAPER_CONFIGS="$source_dir/tests/e2e/paper" \
  PAPER_SHAPES="spheres ovoids-0.5" PAPER_OUT="$killed"
[ ! -e "$killed/spheres/r1/dem/load.done" ] || fail "the load finished before it was killed; nothing was interrupted"
# The partial export of the killed study: what it finished (the spheres' preparation, the checkpoints
# written), nothing it did not, and no comparison yet; a shape not started is left out.
paper paper-export-partial PAPER_OUT="$killed" PAPER_EXPORT="$work/partial" >"$work/partial.log" 2>&1 \
  || fail "make paper-export-partial failed: $(tail -5 "$work/partial.log")"
[ -s "$work/partial/spheres/prepare.log" ] || fail "the partial export lacks the spheres' prepare.log"
written=$(ls "$killed/spheres/r1/dem" | grep -c '^load_[0-9]*\.h5$' || true)
[ "$(($(wc -l < "$work/partial/spheres/static_states.csv") - 1))" = "$written" ] \
  || fail "the partial static_states.csv does not list the $written checkpoints written"
[ ! -e "$work/partial/comparison.md" ] || fail "the partial export wrote a comparison of an unfinished study"
if [ -d "$killed/ovoids-0.5/r1" ]; then [ -d "$work/partial/ovoids-0.5" ] || fail "ovoids-0.5 started but not exported"
else grep -q "ovoids-0.5: .* not started, left out" "$work/partial.log" || fail "no line on the shape not started"; fi
paper paper PAPER_OUT="$killed" >"$work/rerun.log" 2>&1 || fail "the rerun after the kill failed: $(tail -5 "$work/rerun.log")"
grep -q "resuming the interrupted load from $killed/spheres/r1/dem/load_resume.h5" "$work/rerun.log" \
  || fail "the rerun did not resume the load from a checkpoint: $(grep -i 'load' "$work/rerun.log" | head -3)"
! grep -q '^\[prepare\] .*spheres' "$work/rerun.log" || fail "the rerun prepared the spheres again"
"$source_dir/tests/workflows/compare_runs.py" "$reference" "$killed" || fail "the killed-and-rerun paper campaign differs"

# A rerun finds every campaign and the figures up to date.
for shape in spheres ovoids-0.5; do
  make -s -C "$source_dir/workflows" -q campaign CONFIG="$killed/configs/$shape-r1.toml" OUT="$killed/$shape/r1" \
    BIN="$build_dir" || fail "a rerun of $shape's finished campaign would redo work"
done
paper -q paper-figures PAPER_OUT="$killed" || fail "a rerun of the finished paper figures would redo work"

# Refused before anything runs, with the reason.
for bad in "REALISATIONS=0|REALISATIONS = '0': expected an integer >= 1" \
           "PAPER_SHAPES=ovoids-0.7|PAPER_SHAPES names 'ovoids-0.7'"; do
  setting=${bad%%|*} message=${bad#*|}
  if make -s -C "$source_dir/workflows" paper BIN="$build_dir" PAPER_CONFIGS="$source_dir/tests/e2e/paper" \
    PAPER_OUT="$work/refused" "$setting" >"$work/refused.log" 2>&1; then fail "make paper $setting ran"; fi
  grep -qF "$message" "$work/refused.log" || fail "make paper $setting: no '$message' in $(cat "$work/refused.log")"
  [ ! -e "$work/refused" ] || fail "make paper $setting wrote $work/refused"
done
echo "paper e2e: all checks passed"
