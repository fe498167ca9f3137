# shellcheck shell=bash
# Sourced by the tests that need a real single-node SLURM cluster (slurm_campaign.sh,
# slurm_large_load.sh): `slurm_test_cluster_check NAME` skips the test (exit 77) without root or
# SLURM; `slurm_test_cluster NAME` starts a private cluster (workflows/slurm/local-cluster.sh: its own state folder and two free
# ports, so that it cannot meet another cluster) and exports SLURM_CONF. The daemons are stopped on
# every exit, and a watchdog stops them before ctest's SIGKILL (which no trap sees) when the test
# has run SLURM_TEST_LIMIT seconds (840 by default).
# Needs: fail (the test's own), source_dir.

slurm_test_cluster_check() {
  local name=$1
  if [[ $(id -u) -ne 0 ]]; then
    echo "$name: skipped: the local test cluster needs root (SlurmUser=root)"
    exit 77
  fi
  for program in slurmctld slurmd munged sbatch h5diff; do
    command -v "$program" >/dev/null || {
      echo "$name: skipped: $program not found (scripts/install-deps.sh installs slurm-wlm munge libpmix2)"
      exit 77
    }
  done
}

# shellcheck disable=SC2154 # source_dir is the sourcing test's
slurm_test_cluster() {
  local name=$1
  slurm_test_cluster_check "$name"
  cluster=$source_dir/workflows/slurm/local-cluster.sh
  # A short state path: munge's socket path is limited to 108 bytes.
  export ANISO_SLURM_DIR
  ANISO_SLURM_DIR=$(mktemp -d /tmp/aniso-slurm-test.XXXXXX)
  # Open MPI names its shared-memory segments after the SLURM job (vader_segment.<host>.<job>...),
  # which every private cluster numbers from 1: two of these tests on one host at once (a CI and
  # a fresh-machine run, 2026-12-07) mapped each other's segments and crashed inside MPI_Allreduce.
  # Each cluster's ranks keep theirs in its own folder.
  export OMPI_MCA_btl_vader_backing_directory=$ANISO_SLURM_DIR
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
  trap slurm_test_cluster_stop EXIT
  trap 'exit 130' INT TERM
  # ctest kills a test that overruns its TIMEOUT with SIGKILL, which no trap sees, and bash runs
  # a trap only once the command in progress ends: so a watchdog stops the daemons itself first.
  (
    # shellcheck disable=SC2217 # no stdin or stdout: the sleep must hold no pipe of ctest's
    sleep $((${SLURM_TEST_LIMIT:-840} - SECONDS)) </dev/null >/dev/null 2>&1
    echo "$name: FAIL: over the time limit; stopping the cluster" >&2
    "$cluster" stop
    kill -TERM $$
  ) &
  watchdog=$!
  eval "$("$cluster" start)"
  [[ -n ${SLURM_CONF:-} ]] || fail "local-cluster.sh start printed no SLURM_CONF"
}

slurm_test_cluster_stop() {
  local code=$?
  # The watchdog's sleep must go too: it would hold ctest's output pipe open until it ends.
  [[ -z ${watchdog:-} ]] || { pkill -P "$watchdog" 2>/dev/null; kill "$watchdog" 2>/dev/null; } || true
  ANISO_SLURM_KEEP=0 "$cluster" stop || true
  rm -rf "$ANISO_SLURM_DIR"
  exit $code
}
