#!/usr/bin/env bash
# The SLURM path for real: starts a single-node SLURM cluster on localhost
# (workflows/slurm/local-cluster.sh), submits the e2e campaign with
# workflows/slurm/submit.py, waits for its jobs and checks that every result
# equals a local `make campaign` of the same config bit for bit
# (compare_runs.py says what it compares). Then a second
# submission must find nothing to do. The daemons are stopped on every exit.
#
# usage: slurm_campaign.sh SOURCE_DIR BUILD_DIR WORK_DIR
# Exits 77 (ctest: skipped) when not root or SLURM is not installed, saying why.
set -euo pipefail
source_dir=$1 build_dir=$2 work=$3
fail() {
  echo "slurm_campaign: FAIL: $*" >&2
  exit 1
}

# shellcheck source=tests/workflows/slurm_test_cluster.sh
source "$source_dir/tests/workflows/slurm_test_cluster.sh"
slurm_test_cluster_check slurm_campaign

rm -rf "$work"
mkdir -p "$work"
workflows=$source_dir/workflows
config=$workflows/configs/e2e.toml
# The reference: the same campaign run locally, one process per stage.
make -s -C "$workflows" campaign CONFIG="$config" OUT="$work/local" BIN="$build_dir" >"$work/local.log" 2>&1 \
  || fail "local campaign failed: $(tail -5 "$work/local.log")"
! grep -q 'campaign: skipping' "$work/local.log" || fail "the local campaign skipped a stage: $(grep 'skipping' "$work/local.log")"

started=$SECONDS
slurm_test_cluster slurm_campaign
"$workflows/slurm/submit.py" --config "$config" --out "$work/slurm" --bin "$build_dir" --wait \
  2>"$work/submit.log" || fail "SLURM campaign failed: $(cat "$work/submit.log"; tail -20 "$work"/slurm/slurm/*.log)"
echo "slurm_campaign: SLURM campaign done in $((SECONDS - started)) s"

# Every step ran as its own job, in dependency order, through srun.
grep -q 'submit: prepare: job' "$work/submit.log" || fail "no prepare job was submitted"
grep -q 'submit: load: job [0-9]*, after [0-9]' "$work/submit.log" || fail "the load job did not wait for prepare"
grep -q 'submit: report: job [0-9]*, after [0-9]*,[0-9]' "$work/submit.log" || fail "the report job did not wait for all"
[[ $(grep -c 'completed$' "$work/submit.log") -eq $(wc -l <"$work/slurm/slurm/jobs.tsv") ]] \
  || fail "not every job completed: $(cat "$work/submit.log")"
grep -q 'srun .*aniso-dem load' "$work"/slurm/slurm/load-*.log || fail "the load did not run through srun"

"$source_dir/tests/workflows/compare_runs.py" "$work/local" "$work/slurm" \
  || fail "the SLURM campaign's results differ from the local run's"

# The comparison itself must see a one-ulp change in one number.
mkdir -p "$work/ulp/a" "$work/ulp/b"
cp "$work/local/dem/history.h5" "$work/ulp/a/"
cp "$work/local/dem/history.h5" "$work/ulp/b/"
/usr/bin/python3 - "$work/ulp/b/history.h5" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    p = f["history/p"]
    values = p[()]
    values[-1] = np.nextafter(values[-1], np.inf)
    p[...] = values
PY
if "$source_dir/tests/workflows/compare_runs.py" "$work/ulp/a" "$work/ulp/b" 2>"$work/ulp.log"; then
  fail "compare_runs.py missed a one-ulp change in history.h5"
fi
grep -q 'history.h5 differs: /history/p: values' "$work/ulp.log" || fail "compare_runs.py: $(cat "$work/ulp.log")"

# Resubmitting a finished campaign submits nothing.
"$workflows/slurm/submit.py" --config "$config" --out "$work/slurm" --bin "$build_dir" --wait 2>"$work/resubmit.log" \
  || fail "resubmission failed: $(cat "$work/resubmit.log")"
grep -q 'nothing to submit' "$work/resubmit.log" || fail "resubmission redid work: $(cat "$work/resubmit.log")"

# The job-array plumbing of the analysis stages, with command-line doubles of
# the stages (stage_double.py: text files naming the job and task that wrote
# them, so that this part runs in seconds and also before a stage is built),
# on the finished run's first checkpoint alone: a 7-task probe array
# (reference and six increments) then its collection, voxel then a 3-task LBM
# array then its collection; fabric after the load, the fabric series after
# all analyses, the report last. Probe fork 3 fails the first time: its
# collection, the series and the report must be cancelled, everything else
# must finish, and a resubmission must submit only what is missing and redo
# no finished task.
arrays=$work/arrays
arrays_config=$work/arrays.toml
sed 's/^checkpoint_strains = .*/checkpoint_strains = [1e-4]/' "$config" >"$arrays_config"
touch -d '2000-01-01' "$arrays_config" # older than the copied run, which stays up to date
mkdir -p "$arrays/dem"
cp -a "$work/slurm"/dem/{prepared.h5,load_000.h5,history.h5,history.csv,load.done} "$arrays/dem/"
cp -a "$work/slurm/figures" "$arrays/"
fakebin=$work/fakebin
mkdir -p "$fakebin"
ln -s "$build_dir/dem" "$fakebin/dem"
for stage in fabric probe voxel lbm; do
  mkdir -p "$fakebin/$stage"
  printf '#!/bin/sh\nexec /usr/bin/python3 %s %s "$@"\n' "$source_dir/tests/workflows/stage_double.py" "$stage" \
    >"$fakebin/$stage/aniso-$stage"
  chmod +x "$fakebin/$stage/aniso-$stage"
done
# The doubles' results are placeholders, not HDF5: the figures of the stages are not drawn.
submit_arrays() { PLOT_STAGES=none "$workflows/slurm/submit.py" --config "$arrays_config" --out "$arrays" --bin "$fakebin" "$@"; }
if STAGE_DOUBLE_FAIL=probe_load_000_fork3 submit_arrays --wait 2>"$work/arrays-failing.log"; then
  fail "submit.py --wait returned 0 although a probe fork failed"
fi
grep -q 'probe-load_000: job [0-9]* task 3 ended FAILED; log: .*/probe-load_000-[0-9]*_3.log' "$work/arrays-failing.log" \
  || fail "the failed fork was not reported: $(cat "$work/arrays-failing.log")"
[[ $(grep -c 'probe-load_000: job [0-9]* task' "$work/arrays-failing.log") -eq 1 ]] || fail "tasks other than 3 reported"
for step in probe-collect-load_000 series report; do
  grep -q "$step: job [0-9]* ended CANCELLED" "$work/arrays-failing.log" \
    || fail "$step was not cancelled after its dependency failed: $(cat "$work/arrays-failing.log")"
done
[[ $(grep -c 'completed$' "$work/arrays-failing.log") -eq 4 ]] \
  || fail "fabric, voxel, lbm and lbm-collect, which do not need the failed fork, did not complete: $(cat "$work/arrays-failing.log")"
grep -q 'stage_double: failing on purpose' "$arrays"/slurm/probe-load_000-*_3.log || fail "fork 3's log lacks its error"
[[ ! -e $arrays/probe/probe_load_000_fork3.h5 && ! -e $arrays/probe/probe_load_000.h5 ]] || fail "a failed step left a result"
written_before=$(stat -c '%n %Y' "$arrays"/probe/probe_load_000_fork[012456].h5 "$arrays"/voxel/voids_*.h5 "$arrays"/fabric/fabric.h5)

submit_arrays --wait 2>"$work/arrays.log" || fail "the resubmission failed: $(cat "$work/arrays.log")"
[[ $(grep -v 'completed$' "$work/arrays.log" | grep -Eo '^submit: [^:]+: job [0-9]+' | cut -d' ' -f2 | tr '\n' ' ') == \
  "probe-load_000: probe-collect-load_000: series: report: " ]] \
  || fail "the resubmission should submit exactly the failed array, its collection, the series and the report: $(cat "$work/arrays.log")"
[[ $written_before == "$(stat -c '%n %Y' "$arrays"/probe/probe_load_000_fork[012456].h5 "$arrays"/voxel/voids_*.h5 "$arrays"/fabric/fabric.h5)" ]] \
  || fail "the resubmission rewrote finished results"
/usr/bin/python3 - "$arrays" "$work/arrays-failing.log" "$work/arrays.log" <<'PY' || fail "job-array plumbing"
import re, sys
run = sys.argv[1]
jobs = {}  # step -> [(job id, array text, after)] over both submissions
for log in sys.argv[2:]:
    for name, job, array, after in re.findall(
            r"^submit: (\S+): job (\d+)( \((?:array of \d+|tasks [\d,]+ of \d+)\))?(?:, after ([\d,]+))?$",
                                             open(log).read(), re.M):
        jobs.setdefault(name, []).append((job, array, after))
assert "prepare" not in jobs and "load" not in jobs, f"finished steps were resubmitted: {sorted(jobs)}"
ids = lambda name: [j[0] for j in jobs[name]]
def fields(path):
    return dict(f.split("=", 1) for f in open(path).read().split() if "=" in f)
stem = "load_000"
# The failed fork alone is resubmitted, not the whole array.
assert [j[1] for j in jobs[f"probe-{stem}"]] == [" (array of 7)", " (tasks 3 of 7)"], jobs[f"probe-{stem}"]
assert all(j[1] == " (array of 3)" for j in jobs[f"lbm-{stem}"]), jobs[f"lbm-{stem}"]
for k in range(7):
    f = fields(f"{run}/probe/probe_{stem}_fork{k}.h5")
    expected = ids(f"probe-{stem}")[1 if k == 3 else 0]  # fork 3 ran again in the second submission
    assert f["SLURM_ARRAY_JOB_ID"] == expected and f["SLURM_ARRAY_TASK_ID"] == str(k) and f["fork"] == str(k), \
        f"fork {k}: {f}"
for d in range(3):
    f = fields(f"{run}/lbm/permeability_image_{stem}_direction{d}.h5")
    assert f["SLURM_ARRAY_JOB_ID"] == ids(f"lbm-{stem}")[0] and f["SLURM_ARRAY_TASK_ID"] == str(d) \
        and f["direction"] == str(d), f"direction {d}: {f}"
for (job, _, after), upstream in zip(jobs[f"probe-collect-{stem}"], ids(f"probe-{stem}")):
    assert after == upstream, "probe collect must wait for its forks"
assert jobs[f"lbm-{stem}"][0][2] == ids(f"voxel-{stem}")[0], "the LBM array must wait for its image"
assert jobs[f"lbm-collect-{stem}"][0][2] == ids(f"lbm-{stem}")[0], "LBM collect must wait for its directions"
assert fields(f"{run}/probe/probe_{stem}.h5")["SLURM_JOB_ID"] == ids(f"probe-collect-{stem}")[-1]
assert sorted(jobs["series"][0][2].split(",")) == sorted(j[0][0] for n, j in jobs.items()
                                                       if n not in ("series", "report")), \
    "the series must wait for every analysis job"
assert sorted(jobs["report"][0][2].split(",")) == sorted(j[0][0] for n, j in jobs.items() if n != "report"), \
    "the report must wait for every other job"
series = open(f"{run}/fabric/fabric_series.h5").read()
assert all(f"/{name}_{stem}.h5" in series for name in ("probe", "voids", "permeability_image")), series
print(f"slurm_campaign: {len(jobs)} analysis steps, arrays, dependencies, failure and recovery as planned")
PY
submit_arrays 2>"$work/arrays-again.log"
grep -q 'nothing to submit' "$work/arrays-again.log" || fail "resubmission redid analyses: $(cat "$work/arrays-again.log")"
echo "slurm_campaign: all checks passed"
