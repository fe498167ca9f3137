#!/usr/bin/env bash
# The cluster recipe for a load longer than a job (workflows/slurm/large-load.sh, docs/cluster.md)
# on a real single-node SLURM cluster: a prepared assembly tiled 2 x 2 x 2, loaded on 2 tasks by a
# chain of jobs. The first job is sent SIGTERM after its first checkpoint (as SLURM does before a
# time limit, sbatch --signal): it must submit the next job itself, which resumes and finishes; the
# history and every checkpoint must equal an uninterrupted local run of the same tiling bit for
# bit. Bad submissions are refused before anything is submitted.
#
# usage: slurm_large_load.sh SOURCE_DIR BUILD_DIR WORK_DIR
# Exits 77 (ctest: skipped) when not root or SLURM is not installed, saying why.
set -euo pipefail
source_dir=$1 build_dir=$2 work=$3
fail() {
  echo "slurm_large_load: FAIL: $*" >&2
  exit 1
}
# shellcheck source=tests/workflows/slurm_test_cluster.sh
source "$source_dir/tests/workflows/slurm_test_cluster.sh"
slurm_test_cluster_check slurm_large_load
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
dem=$build_dir/dem/aniso-dem
recipe=$source_dir/workflows/slurm/large-load.sh
rm -rf "$work"
mkdir -p "$work"

# 200 spheres prepared, then the load's configuration without a particle count (the tiled file's).
"$dem" prepare --config "$source_dir/workflows/configs/e2e.toml" --set dem.output_dir="$work/prep" \
  --log-level warn
config=$work/large.toml
cat >"$config" <<'TOML'
[dem]
seed = 3
[dem.load]
final_strain = 0.004
history_interval = 2e-4
checkpoint_strains = [1e-4, 0.002, 0.004]
TOML

# Refused before anything is submitted: --copies without --from, a missing input, a bad margin.
for bad in "--copies 2,2,2" "--from $work/none.h5 --copies 2,2,2" "--from $work/prep/prepared.h5"; do
  # shellcheck disable=SC2086 # the options are words
  if "$recipe" --config "$config" --out "$work/refused" --bin "$build_dir" $bad --dry-run 2>"$work/refused.log"; then
    fail "large-load.sh accepted '$bad'"
  fi
  grep -q 'large-load: error:' "$work/refused.log" || fail "no clear message for '$bad': $(cat "$work/refused.log")"
done
"$recipe" --config "$config" --out "$work/refused" --bin "$build_dir" --from "$work/prep/prepared.h5" \
  --copies 2,2,2 --margin soon --dry-run 2>"$work/refused.log" && fail "large-load.sh accepted --margin soon"
grep -q "margin 'soon'" "$work/refused.log" || fail "no clear message for a bad margin: $(cat "$work/refused.log")"

# The reference: the same tiling loaded locally, uninterrupted.
"$dem" replicate --input "$work/prep/prepared.h5" --output "$work/ref/prepared.h5" --copies 2,2,2 --log-level warn
mpiexec --oversubscribe -n 2 "$dem" load --config "$config" --set dem.output_dir="$work/ref" \
  --input "$work/ref/prepared.h5" --log-level warn

slurm_test_cluster slurm_large_load
run=$work/slurm
"$recipe" --config "$config" --out "$run" --bin "$build_dir" --from "$work/prep/prepared.h5" --copies 2,2,2 \
  --margin 60 -- -n 2 --time=10 >"$work/submit.log" || fail "large-load.sh failed: $(cat "$work/submit.log")"
first=$(sed -n 's/^large-load: submitted job \([0-9]*\).*/\1/p' "$work/submit.log")
[[ -n $first ]] || fail "no job submitted: $(cat "$work/submit.log")"
grep -q '^#SBATCH --signal=TERM@60$' "$run/slurm/large-load.job" || fail "the job asks for no SIGTERM before its limit"

# SIGTERM to the first job's load once it has written its first checkpoint.
for _ in $(seq 600); do
  [[ -s $run/dem/load_000.h5 ]] && break
  sleep 0.2
done
[[ -s $run/dem/load_000.h5 ]] || fail "the first job wrote no checkpoint: $(cat "$run"/slurm/large-load-*.log)"
scancel --signal=TERM "$first"
for _ in $(seq 900); do
  [[ -e $run/dem/load.done ]] && break
  sleep 0.5
done
logs=$(cat "$run"/slurm/large-load-*.log)
[[ -e $run/dem/load.done ]] || fail "the chain did not finish the load: $logs"
second=$(sed -n 's/.*the load continues in job \([0-9]*\).*/\1/p' "$run/slurm/large-load-$first.log")
[[ -n $second ]] || fail "the first job did not submit the next after SIGTERM: $logs"
grep -q 'the load is done' "$run/slurm/large-load-$second.log" || fail "job $second did not finish: $logs"
grep -q 'resuming the interrupted load from .*load_interrupted.h5' "$run/slurm/large-load-$second.log" \
  || fail "job $second did not resume from load_interrupted.h5: $logs"

for file in load_000.h5 load_001.h5 load_002.h5; do
  for group in /particles /contacts /cell; do
    h5diff "$work/ref/$file" "$run/dem/$file" "$group" "$group" >"$work/diff.txt" \
      || fail "$file $group differs from the uninterrupted run: $(head -5 "$work/diff.txt")"
  done
done
h5diff "$work/ref/history.h5" "$run/dem/history.h5" /history /history >"$work/diff.txt" \
  || fail "the history differs from the uninterrupted run: $(head -5 "$work/diff.txt")"
echo "slurm_large_load: job $first stopped by SIGTERM after its first checkpoint, job $second resumed;" \
  "history and 3 checkpoints of 1600 particles equal the uninterrupted run's"
