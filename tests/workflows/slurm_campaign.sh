#!/usr/bin/env bash
# The SLURM path for real: starts a single-node SLURM cluster on localhost
# (workflows/slurm/local-cluster.sh), submits the e2e campaign with
# workflows/slurm/submit.py, waits for its jobs and checks that every result
# equals a local `make campaign` of the same config bit for bit. Then a second
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

if [[ $(id -u) -ne 0 ]]; then
  echo "slurm_campaign: skipped: the local test cluster needs root (SlurmUser=root)"
  exit 77
fi
for program in slurmctld slurmd munged sbatch h5diff; do
  command -v "$program" >/dev/null || {
    echo "slurm_campaign: skipped: $program not found (scripts/install-deps.sh installs slurm-wlm munge libpmix2)"
    exit 77
  }
done

rm -rf "$work"
mkdir -p "$work"
workflows=$source_dir/workflows
config=$workflows/configs/e2e.toml
cluster=$source_dir/workflows/slurm/local-cluster.sh

# A private cluster: its own state folder (short path: munge's socket path is
# limited to 108 bytes) and two free ports, so it cannot meet another cluster.
export ANISO_SLURM_DIR
ANISO_SLURM_DIR=$(mktemp -d /tmp/aniso-slurm-test.XXXXXX)
export ANISO_SLURM_PORT
ANISO_SLURM_PORT=$(/usr/bin/python3 - <<'PY'
import random, socket
def free(port):
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
            return True
        except OSError:
            return False
port = next(p for p in random.sample(range(20000, 30000, 2), 200) if free(p) and free(p + 1))
print(port)
PY
)
stop_cluster() {
  local code=$?
  ANISO_SLURM_KEEP=0 "$cluster" stop || true
  rm -rf "$ANISO_SLURM_DIR"
  exit $code
}
trap stop_cluster EXIT
trap 'exit 130' INT TERM

# The reference: the same campaign run locally, one process per stage.
make -s -C "$workflows" campaign CONFIG="$config" OUT="$work/local" BIN="$build_dir" >"$work/local.log" 2>&1 \
  || fail "local campaign failed: $(tail -5 "$work/local.log")"

started=$SECONDS
eval "$("$cluster" start)"
[[ -n ${SLURM_CONF:-} ]] || fail "local-cluster.sh start printed no SLURM_CONF"
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

"$source_dir/tests/workflows/compare_runs.sh" "$work/local" "$work/slurm" \
  || fail "the SLURM campaign's results differ from the local run's"

# The comparison itself must see a one-ulp change in one number.
cp -r "$work/local" "$work/altered"
/usr/bin/python3 - "$work/altered/history.h5" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    p = f["history/p"]
    values = p[()]
    values[-1] = np.nextafter(values[-1], np.inf)
    p[...] = values
PY
if "$source_dir/tests/workflows/compare_runs.sh" "$work/local" "$work/altered" 2>/dev/null; then
  fail "compare_runs.sh missed a one-ulp change in history.h5"
fi

# Resubmitting a finished campaign submits nothing.
"$workflows/slurm/submit.py" --config "$config" --out "$work/slurm" --bin "$build_dir" --wait 2>"$work/resubmit.log" \
  || fail "resubmission failed: $(cat "$work/resubmit.log")"
grep -q 'nothing to submit' "$work/resubmit.log" || fail "resubmission redid work: $(cat "$work/resubmit.log")"
echo "slurm_campaign: all checks passed"
