#!/usr/bin/env bash
# The body of every SLURM job of the campaign (submitted by submit.py): runs
# `make` in workflows/ for the job's own targets. In a job array, "{task}" in
# any argument becomes the array index. Upstream targets come as "-o FILE"
# arguments, so a job never remakes the files of the jobs it waited for.
#
#   make-step.sh WORKFLOWS_DIR MAKE_ARGUMENT...
#
# ANISO_SLURM_LAUNCHER (default: srun) starts the stage executables inside the
# allocation; it becomes the Makefile's RUN.
set -euo pipefail # without -e a job would end COMPLETED even when a stage fails

workflows=$1
shift
task=${SLURM_ARRAY_TASK_ID:-0}
arguments=()
for argument in "$@"; do
  arguments+=("${argument//\{task\}/$task}")
done
echo "make-step: job ${SLURM_JOB_ID:-?} task $task on $(hostname) at $(date -u +%FT%TZ): ${SLURM_NTASKS:-1} tasks"
make -C "$workflows" "RUN=${ANISO_SLURM_LAUNCHER:-srun}" "${arguments[@]}"
echo "make-step: done at $(date -u +%FT%TZ)"
