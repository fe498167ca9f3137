#!/usr/bin/env bash
# A/B wall time of two aniso-dem binaries on one checkpoint: a fixed-cell hold of STEPS steps
# (`aniso-dem hold`: the force pass, the integration, the ghost refresh and migration of a
# loading step, without the cell control) on RANKS ranks, REPEATS interleaved rounds so that
# the host's noise hits both alike. Prints each run, then the median wall time of each binary,
# their ratio and particle-steps per second; checks that both wrote the same CSV (p, q and
# the equilibrium ratios at every control update), i.e. the same trajectory to the last bit.
#
# usage: tests/perf/dem_ranks/ab.sh BIN_A BIN_B CHECKPOINT [RANKS=2] [STEPS=3000] [REPEATS=5] [WORK=/tmp/aniso-ab]
set -euo pipefail
a=$1 b=$2 checkpoint=$3 ranks=${4:-2} steps=${5:-3000} repeats=${6:-5} work=${7:-/tmp/aniso-ab}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$work"
particles=$(h5dump -H "$checkpoint" | awk '/DATASET "id"/ {found=1} found && /DATASPACE/ {gsub(/[^0-9 ]/, " "); print $1; exit}')
echo "checkpoint $checkpoint: $particles particles; $ranks ranks, $steps steps, $repeats rounds; load average $(cut -d' ' -f1-3 /proc/loadavg)"
: >"$work/times.txt"
for round in $(seq "$repeats"); do
  for name in A B; do
    bin=$a
    [[ $name == B ]] && bin=$b
    start=$(date +%s.%N)
    mpirun --oversubscribe -np "$ranks" "$bin" hold --input "$checkpoint" --steps "$steps" --csv "$work/$name.csv" \
      --log-level warn
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    echo "$name $round $wall" | tee -a "$work/times.txt"
  done
done
cmp -s "$work/A.csv" "$work/B.csv" && echo "same trajectory: the CSVs are identical" || echo "THE CSVs DIFFER"
/usr/bin/python3 - "$work/times.txt" "$particles" "$steps" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
particles, steps = int(sys.argv[2]), int(sys.argv[3])
median = {n: statistics.median(float(w) for m, _, w in rows if m == n) for n in ("A", "B")}
for n, t in median.items():
    print(f"{n}: median {t:.2f} s, {particles * steps / t:.3g} particle-steps/s (start-up included)")
print(f"A / B = {median['A'] / median['B']:.3f}")
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
