#!/usr/bin/env bash
# The body of every SLURM job of the campaign (submitted by submit.py): runs
# `make` in workflows/ for the job's own targets. In a job array, "{task}" in
# any argument becomes the array index. The files of the jobs it waited for
# come as --upstream=FILE: they must be up to date (make -q) before the job
# starts, so no job ever remakes another job's files.
#
#   make-step.sh WORKFLOWS_DIR [--upstream=FILE...] MAKE_ARGUMENT...
#
# ANISO_SLURM_LAUNCHER (default: srun) starts the stage executables inside the
# allocation; it becomes the Makefile's RUN.
set -euo pipefail # without -e a job would end COMPLETED even when a stage fails

workflows=$1
shift
task=${SLURM_ARRAY_TASK_ID:-0}
upstream=()
arguments=()
variables=()
for argument in "$@"; do
  argument=${argument//\{task\}/$task}
  case $argument in
    --upstream=*) upstream+=("${argument#--upstream=}") ;;
    *=*) variables+=("$argument") ;;
    *) arguments+=("$argument") ;;
  esac
done
# Threaded stages (aniso-voxel) stay within the job's CPUs: --cpus-per-task, else one per task.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}
echo "make-step: job ${SLURM_JOB_ID:-?} task $task on $(hostname) at $(date -u +%FT%TZ): ${SLURM_NTASKS:-1} tasks"
if [[ ${#upstream[@]} -gt 0 ]] && ! make -q -C "$workflows" "${variables[@]}" "${upstream[@]}"; then
  echo "make-step: error: the files this job depends on are missing or out of date: ${upstream[*]}" >&2
  echo "make-step: (did an input change after submission?) rerun workflows/slurm/submit.py" >&2
  exit 1
fi
make -C "$workflows" "RUN=${ANISO_SLURM_LAUNCHER:-srun}" "${variables[@]}" "${arguments[@]}"
echo "make-step: done at $(date -u +%FT%TZ)"
