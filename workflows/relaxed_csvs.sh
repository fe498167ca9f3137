#!/bin/bash
# Issue 21, section 4: the committed CSVs of a shape's relaxed checkpoints, from what
# workflows/relax_and_probe.sh has finished so far: the fabric series of the relaxed checkpoints with
# their probe results (aniso-fabric series) and each probe's CSV, and apart (probes_unchecked/) those
# of probes the linearity check refused, run again with probe.check_increment = false into
# runs/paper-SHAPE/relaxed/unchecked/. Rerun as more checkpoints finish.
# usage: workflows/relaxed_csvs.sh SHAPE   (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)
#   reads runs/paper-SHAPE/relaxed/, writes docs/paper-size/<folder>/relaxed/{fabric_series*.csv,relax_steps.csv,probes/}
#   (<folder>: spheres or ovoids-0.8 ...); BIN=<build dir> (default build)
# KEEP_COMMITTED=1: a run folder rebuilt in part (lost with its host) keeps the committed rows of the
#   checkpoints it lacks in fabric_series.csv and relax_steps.csv (merge_committed_rows.py; the probe
#   CSVs of those checkpoints stay as committed); fabric_series_correlations.csv is then over the
#   run folder's checkpoints only (its n_points says how many).
set -euo pipefail
cd "$(dirname "$0")/.."  # the repository root
shape=${1:?usage: workflows/relaxed_csvs.sh SHAPE (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)}
relaxed=runs/paper-$shape/relaxed
config=workflows/configs/paper-$shape.toml
out=docs/paper-size/$shape/relaxed
bin=${BIN:-build}
[ -f "$config" ] || { echo "relaxed_csvs.sh: no config $config" >&2; exit 2; }
compgen -G "$relaxed/load_0*.h5" > /dev/null ||
  { echo "relaxed_csvs.sh: no relaxed checkpoints $relaxed/load_0*.h5 (run workflows/relax_and_probe.sh $shape)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
probes=()  # the probes that passed their checks, if any
compgen -G "$relaxed/probe_load_0*.h5" > /dev/null && probes=(--probe "$relaxed"/probe_load_0*.h5)
"$bin/fabric/aniso-fabric" series --config "$config" --input "$relaxed"/load_0*.h5 "${probes[@]}" \
  --output "$work/fabric_series.h5" --log-level warn
mkdir -p "$out"
keep() {  # keep FILE KEY: the committed rows of checkpoints this run folder lacks (KEEP_COMMITTED=1)
  [ "${KEEP_COMMITTED:-0}" = 1 ] || return 0
  kept=$(/usr/bin/python3 workflows/merge_committed_rows.py "$work/$1" "$out/$1" "$2")
  [ -z "$kept" ] || echo "relaxed_csvs.sh: $1 keeps the committed rows of $kept"
}
keep fabric_series.csv source
cp "$work/fabric_series.csv" "$work/fabric_series_correlations.csv" "$out/"
if [ ${#probes[@]} -gt 0 ]; then
  mkdir -p "$out/probes"
  cp "$relaxed"/probe_load_0*.csv "$out/probes/"
fi
# Probes the linearity check refused, run again with probe.check_increment = false (kept apart: flagged).
if compgen -G "$relaxed/unchecked/probe_load_0*.csv" > /dev/null; then
  mkdir -p "$out/probes_unchecked"
  cp "$relaxed"/unchecked/probe_load_0*.csv "$out/probes_unchecked/"
fi
# What each relaxation took (from aniso-dem relax's closing log line): steps, the verification windows
# it left and had to relax again after, and the state before and after; verified: false for a
# relaxation without the verification window (relax_and_probe.sh's "# settings:" line says
# verify_steps=0: the critical state's settings, or the fallback after a verified attempt failed);
# attempt_restarts: the windows such a failed attempt left (relax_<stem>.unverified_attempt.log).
{
  echo "checkpoint,steps,restarts,p_before_Pa,p_after_Pa,e_before,e_after,force_ratio_before,force_ratio_after,verified,attempt_restarts"
  for log in "$relaxed"/relax_load_0??.log; do
    line=$(grep "info relax of" "$log") || continue  # still running
    restarts=$(grep -c "relaxing again" "$log" || true)
    verified=true
    grep -q "^# settings:.*verify_steps=0" "$log" && verified=false
    attempt=${log%.log}.unverified_attempt.log
    attempt_restarts=0
    [ -f "$attempt" ] && attempt_restarts=$(grep -c "relaxing again" "$attempt" || true)
    row=$(echo "$line" | sed -nE 's/.*relax of .*\/(load_[0-9]+)\.h5.: ([0-9]+) steps( \([^)]*\))?, p ([^ ]+) -> ([^ ]+) Pa, void ratio ([^ ]+) -> ([^ ]+), unbalanced-force ratio ([^ ]+) -> ([^,]+),.*/\1,\2,'"$restarts"',\4,\5,\6,\7,\8,\9,'"$verified,$attempt_restarts"'/p')
    [ -n "$row" ] || { echo "relaxed_csvs.sh: $log: the closing line is not aniso-dem relax's 'relax of ...: N steps, p ... -> ... Pa, void ratio ..., unbalanced-force ratio ...' (format changed?)" >&2; exit 3; }
    echo "$row"
  done
} > "$work/relax_steps.csv"
keep relax_steps.csv checkpoint
cp "$work/relax_steps.csv" "$out/"  # only once every row parsed
echo "relaxed_csvs.sh: $(ls "$relaxed"/load_0*.h5 | wc -l) relaxed checkpoints, $(ls "$relaxed"/probe_load_0*.csv 2> /dev/null | wc -l) probes, $(ls "$relaxed"/unchecked/probe_load_0*.csv 2> /dev/null | wc -l) unchecked -> $out"
