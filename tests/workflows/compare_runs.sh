#!/usr/bin/env bash
# Checks that run folder B holds every result of run folder A with the same
# bits: HDF5 files dataset by dataset and attribute by attribute with h5diff
# (leaving out /provenance, which records the date, command line and rank
# count), CSV and PNG files byte for byte, report.md after replacing each
# folder's own path. Job logs (slurm/) and the load.done stamp are not results.
#
# usage: compare_runs.sh RUN_A RUN_B      exit 0 when identical, 1 with the differing files named
set -euo pipefail
a=$1 b=$2
differ=0
compared=0
note() { echo "compare_runs: $*" >&2; }

while IFS= read -r -d '' path; do
  file=${path#"$a"/}
  if [[ ! -e $b/$file ]]; then
    note "$file is in $a but not in $b"
    differ=1
    continue
  fi
  case $file in
    *.h5)
      if ! h5diff --exclude-path /provenance "$a/$file" "$b/$file" >/dev/null 2>&1; then
        note "$file differs (h5diff --exclude-path /provenance $a/$file $b/$file)"
        differ=1
      fi
      ;;
    *.md)
      if ! diff <(sed "s|$a|RUN|g" "$a/$file") <(sed "s|$b|RUN|g" "$b/$file") >/dev/null; then
        note "$file differs beyond the run folder's name"
        differ=1
      fi
      ;;
    *)
      cmp -s "$a/$file" "$b/$file" || {
        note "$file differs byte for byte"
        differ=1
      }
      ;;
  esac
  compared=$((compared + 1))
done < <(find "$a" -type f ! -path "$a/slurm/*" ! -name load.done ! -name '.*' -print0 | sort -z)

[[ $compared -gt 0 ]] || {
  note "no results in $a"
  exit 1
}
[[ $differ -eq 0 ]] && note "$compared files identical in $a and $b"
exit $differ
