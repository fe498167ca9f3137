#!/usr/bin/env bash
# Snakemake 7 against workflows/slurm/submit.py on the local SLURM test cluster
# (workflows/slurm/local-cluster.sh): the e2e campaign (200 spheres, 3 checkpoints,
# every stage), run by each; then one probe fork deleted and each run again.
# Prints wall times and job counts; checks that both wrote the same results
# (tests/workflows/compare_runs.py). Needs root, slurm-wlm munge libpmix2 and snakemake.
#
# usage: tests/perf/workflow_snakemake/run.sh BUILD_DIR WORK_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$here/../../.." && pwd)
build=$(cd "$1" && pwd) work=$2
config=$source_dir/workflows/configs/e2e.toml
cluster=$source_dir/workflows/slurm/local-cluster.sh
rm -rf "$work" && mkdir -p "$work" && work=$(cd "$work" && pwd)
export ANISO_SLURM_DIR=$work/cluster ANISO_SLURM_PORT=${ANISO_SLURM_PORT:-24817}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 USER=${USER:-root}
trap '"$cluster" stop || true' EXIT
eval "$("$cluster" start)"

submit() { "$source_dir/workflows/slurm/submit.py" --config "$config" --out "$work/submit" --bin "$build" --wait; }
snake() {
  mkdir -p "$work/snake/slurm"
  snakemake -s "$here/Snakefile" -d "$work/snake-state" -j 40 --latency-wait 5 \
    --config config="$config" out="$work/snake" bin="$build" run=srun \
    --cluster "sbatch --parsable -n {resources.ranks} -o $work/snake/slurm/%j.log" \
    --cluster-status "$here/slurm_status.sh" --max-status-checks-per-second 1
}
timed() { # timed NAME COMMAND...: wall seconds and the number of sbatch jobs the cluster saw
  local before after start
  before=$(scontrol show config | awk '/^NEXT_JOB_ID/ {print $3}')
  start=$(date +%s.%N)
  "${@:2}" >"$work/$1.log" 2>&1 || { echo "$1 failed: $(tail -5 "$work/$1.log")"; exit 1; }
  after=$(scontrol show config | awk '/^NEXT_JOB_ID/ {print $3}')
  printf '%-22s %6.1f s wall, %3d job ids\n' "$1" "$(echo "$(date +%s.%N) - $start" | bc)" $((after - before))
}
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
timed submit-fresh submit
timed snakemake-fresh snake
"$source_dir/tests/workflows/compare_runs.py" "$work/submit" "$work/snake" 2>&1 | tail -1
rm "$work/submit/probe/probe_load_001_fork3.h5" "$work/snake/probe/probe_load_001_fork3.h5"
timed submit-one-fork submit
timed snakemake-one-fork snake
timed submit-nothing submit
timed snakemake-nothing snake
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
