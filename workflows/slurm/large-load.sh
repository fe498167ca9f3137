#!/usr/bin/env bash
# One long DEM load on SLURM as a chain of jobs, each continuing where the last stopped
# (docs/cluster.md, "A million particles on several nodes"). For loads longer than a job may run:
# every job gets SIGTERM MARGIN seconds before its time limit (sbatch --signal), `aniso-dem load`
# writes load_interrupted.h5 and exits, and the job submits the next one, which resumes from it
# with the same bits as an uninterrupted run. A job killed outright (a lost node) leaves no
# interrupted file: run the same submit command again and the load resumes from its newest
# checkpoint (workflows/campaign.py load-input).
#
#   large-load.sh --config CONFIG --out RUN_DIR [--bin BUILD_DIR] [--from PREPARED.h5 --copies n1,n2,n3]
#                 [--launcher 'srun --mpi=pmix'] [--margin SECONDS] [--dry-run] [-- SBATCH_OPTION...]
#
# --from/--copies tile a prepared assembly into RUN_DIR/dem/prepared.h5 first (`aniso-dem
# replicate`, one task; skipped when that file exists); without them RUN_DIR/dem/prepared.h5 must
# exist. The sbatch options after -- (nodes, tasks, memory, time, partition, account) go into
# RUN_DIR/slurm/large-load.job, which every job of the chain is submitted from. Logs:
# RUN_DIR/slurm/large-load-<job>.log and RUN_DIR/logs/load.log. When the load ends, the job
# touches RUN_DIR/dem/load.done, as `make campaign` does, so that `submit.py --config CONFIG --out
# RUN_DIR` then runs only the analyses.
#
#   large-load.sh --step RUN_DIR     (what each job runs; not for the command line)
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
workflows=$(dirname "$here")
say() { printf 'large-load: %s\n' "$*"; }
fail() {
  say "error: $*" >&2
  exit 2
}

# shellcheck disable=SC2153 # CONFIG, BIN, FROM, COPIES and LAUNCHER come from the settings file
run_step() {
  local run=$1
  local settings=$run/slurm/large-load.env
  [[ -s $settings ]] || fail "$settings is missing: submit with large-load.sh --config ... --out $run"
  # shellcheck source=/dev/null
  source "$settings"
  local dem=$run/dem
  mkdir -p "$run/logs"
  # When this job started: a load_interrupted.h5 newer than it was written by this job's load.
  job_start=$(mktemp "$run/slurm/.job-start.XXXXXX")
  trap 'rm -f "$job_start"' EXIT
  say "job ${SLURM_JOB_ID:-?} on ${SLURM_JOB_NUM_NODES:-1} node(s), ${SLURM_NTASKS:-1} task(s), at $(date -u +%FT%TZ)"
  if [[ ! -s $dem/prepared.h5 ]]; then
    [[ -n $FROM ]] || fail "$dem/prepared.h5 is missing and no --from was given"
    say "tiling $FROM $COPIES into $dem/prepared.h5"
    # shellcheck disable=SC2086 # the launcher is a command with its options
    # Without the load's config: its particle count (if it gives one) is the tiled file's.
    $LAUNCHER -n 1 "$BIN/dem/aniso-dem" replicate --input "$FROM" --copies "$COPIES" \
      --output "$dem/prepared.h5" 2>&1 | tee -a "$run/logs/replicate.log"
    [[ ${PIPESTATUS[0]} -eq 0 ]] || fail "replicate failed (see $run/logs/replicate.log)"
  fi
  local input
  input=$(/usr/bin/python3 "$workflows/campaign.py" load-input "$dem" "$CONFIG") || fail "campaign.py load-input failed"
  # shellcheck disable=SC2086 # the launcher is a command with its options; input is option words
  $LAUNCHER "$BIN/dem/aniso-dem" load --config "$CONFIG" --set dem.output_dir="$dem" $input 2>&1 |
    tee -a "$run/logs/load.log"
  local code=${PIPESTATUS[0]}
  if [[ $code -eq 0 ]]; then
    touch "$dem/load.done"
    say "the load is done at $(date -u +%FT%TZ)"
    return 0
  fi
  # Stopped by SIGTERM: aniso-dem wrote load_interrupted.h5 during this job (under srun the step
  # exits 143, under mpirun 1, so the file decides).
  if [[ -e $dem/load_interrupted.h5 && $dem/load_interrupted.h5 -nt $job_start ]]; then
    local next
    next=$(sbatch --parsable --dependency="afterany:${SLURM_JOB_ID:-0}" "$run/slurm/large-load.job") ||
      fail "stopped by SIGTERM, but sbatch refused the next job: resubmit $run/slurm/large-load.job"
    say "stopped by SIGTERM before the time limit; the load continues in job $next"
    return 0
  fi
  fail "the load failed (exit $code; see $run/logs/load.log)"
}

config='' run='' bin='' from='' copies='' launcher='srun' margin=600 dry_run=0
sbatch_options=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --step) run_step "${2:?--step needs RUN_DIR}"; exit $? ;;
    --config) config=${2:?}; shift 2 ;;
    --out) run=${2:?}; shift 2 ;;
    --bin) bin=${2:?}; shift 2 ;;
    --from) from=${2:?}; shift 2 ;;
    --copies) copies=${2:?}; shift 2 ;;
    --launcher) launcher=${2:?}; shift 2 ;;
    --margin) margin=${2:?}; shift 2 ;;
    --dry-run) dry_run=1; shift ;;
    --) shift; sbatch_options=("$@"); break ;;
    -h | --help) sed -n '2,21p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) fail "unknown argument '$1' (--help lists them)" ;;
  esac
done
[[ -n $config && -n $run ]] || fail "--config and --out are required (--help lists the options)"
[[ -s $config ]] || fail "--config '$config' does not exist"
[[ -z $from || -n $copies ]] || fail "--from needs --copies n1,n2,n3"
[[ -n $from || -z $copies ]] || fail "--copies needs --from PREPARED.h5"
[[ -z $from || -s $from ]] || fail "--from '$from' does not exist"
[[ $margin =~ ^[0-9]+$ ]] || fail "--margin '$margin' is not a whole number of seconds"
bin=$(cd "${bin:-$workflows/../build}" 2>/dev/null && pwd) || fail "--bin: no such build folder"
[[ -x $bin/dem/aniso-dem ]] || fail "$bin/dem/aniso-dem is missing: build it, or give --bin"
mkdir -p "$run/slurm" "$run/dem"
run=$(cd "$run" && pwd)
config=$(readlink -f "$config")
[[ -z $from ]] || from=$(readlink -f "$from")
[[ -n $from || -s $run/dem/prepared.h5 ]] || fail "$run/dem/prepared.h5 is missing: give --from and --copies"
{
  printf 'CONFIG=%q\nBIN=%q\nFROM=%q\nCOPIES=%q\nLAUNCHER=%q\n' "$config" "$bin" "$from" "$copies" "$launcher"
} >"$run/slurm/large-load.env"
job=$run/slurm/large-load.job
{
  echo '#!/usr/bin/env bash'
  echo '#SBATCH --job-name=aniso-large-load'
  echo "#SBATCH --output=$run/slurm/large-load-%j.log"
  echo '#SBATCH --open-mode=append'
  echo "#SBATCH --signal=TERM@$margin"
  for option in "${sbatch_options[@]}"; do echo "#SBATCH $option"; done
  printf 'exec %q --step %q\n' "$here/large-load.sh" "$run"
} >"$job"
if [[ $dry_run -eq 1 ]]; then
  say "would submit $job:"
  cat "$job"
  exit 0
fi
submitted=$(sbatch --parsable "$job") || fail "sbatch refused $job"
say "submitted job $submitted ($job); log $run/slurm/large-load-$submitted.log"
