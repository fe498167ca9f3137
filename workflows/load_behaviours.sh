#!/bin/bash
# The named loading behaviours (dem.load.behaviour; docs/methods/dem.md, "Loading behaviours") on
# the same prepared assemblies: each assembly loaded with its paper config to FINAL strain as
#   inertial      continuous at I = 1e-3, contact damping on sticking contacts (the engine's default)
#   oval          DEMPLA/OVAL's body damping of translation (0.071) and spin (x6), no contact damping
#   quasi_static  increments of 3e-5, each minimised to 1e-3
#   increments    the paper configs' setting before the behaviours: OVAL's increments of 1e-4 relaxed to 1e-2
# with checkpoints at 2%, 10% and FINAL written unrelaxed: a loading with relaxed copies as
# checkpoints (dem.equilibrium.fork_checkpoints, the oval behaviour's) has the same history to the
# bit (tests/dem/fork_checkpoints.sh), and the ovoids' copies can take longer than the loading.
# Each run writes WORK/results/<assembly>_<behaviour>.csv (strain, q13, q23, p, eps_v, void_ratio,
# coordination) and
# WORK/<assembly>_<behaviour>/ (history, checkpoints, log, wall.txt); a run whose CSV exists is skipped.
#
# usage: workflows/load_behaviours.sh BUILD WORK FINAL NAME=CONFIG:PREPARED.h5 ... [-- BEHAVIOUR ...]
set -euo pipefail
build=$(cd "$1" && pwd) work=$2 final=$3
shift 3
assemblies=() behaviours=(inertial oval quasi_static increments)
while [ $# -gt 0 ] && [ "$1" != -- ]; do assemblies+=("$1"); shift; done
[ $# -gt 0 ] && { shift; behaviours=("$@"); }
here=$(cd "$(dirname "$0")" && pwd)
io="/usr/bin/python3 $here/../tests/dem/peer/dempla_io.py"
mkdir -p "$work/results"
for assembly in "${assemblies[@]}"; do
  name=${assembly%%=*} spec=${assembly#*=}
  config=$(cd "$(dirname "${spec%%:*}")" && pwd)/$(basename "${spec%%:*}") prepared=${spec#*:}
  # The config's particle count is the paper's; the assembly's own is what the load uses.
  count=$(h5dump -H -d /particles/diameter "$prepared" | sed -n 's/.*SIMPLE { ( \([0-9]*\) ).*/\1/p')
  for behaviour in "${behaviours[@]}"; do
    run=${name}_$behaviour
    [ -s "$work/results/$run.csv" ] && { echo "$run: done before"; continue; }
    case $behaviour in
      inertial | oval | quasi_static) extra=(--set dem.load.behaviour=$behaviour) ;;
      increments) extra=(--set dem.load.behaviour=inertial --set dem.load.increment=1e-4
                         --set dem.load.increment_tolerance=1e-2) ;;
      *) echo "unknown behaviour '$behaviour'"; exit 2 ;;
    esac
    echo "$run: loading to $final ($(uptime | sed 's/.*load/load/'))"
    start=$SECONDS
    "$build/dem/aniso-dem" load --config "$config" --input "$prepared" --set dem.output_dir="$work/$run" \
      --set dem.particles.count="$count" \
      --set dem.load.final_strain="$final" --set "dem.load.checkpoint_strains=[0.02, 0.1, $final]" \
      --set dem.load.history_interval=5e-4 "${extra[@]}" --set dem.equilibrium.at_checkpoints=false \
      --set dem.equilibrium.fork_checkpoints=false --overwrite >"$work/$run.log" 2>&1
    echo $((SECONDS - start)) >"$work/$run/wall.txt"
    $io aniso "$work/$run/history.csv" "$work/results/$run.csv"
  done
done
