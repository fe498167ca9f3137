#!/bin/bash
# A/B throughput of two builds of bench_dem_steps on the packings that run.sh prepared (run it
# once first): REPEATS rounds, each running every binary on the alpha = 0.5 ovoids and on the
# spheres in turn, so that the host's noise (here +-25% from run to run) hits all alike. Prints
# the median and the fastest run of each binary and shape, and the ovoids/spheres cost ratio of
# each binary against the spheres of all binaries pooled (the sphere path is usually the same
# code). With COUNT_INSTRUCTIONS=1 it also counts the instructions per loading step under
# valgrind's callgrind (100 steps less 0 steps), which are deterministic and so resolve changes
# far smaller than the timing noise.
#
# usage: compare.sh BIN_A BIN_B [STEPS=1000] [REPEATS=7] [WORKDIR=/tmp/aniso-dem-ovoid]
# environment: MODE (load, the default, or hold: bench_dem_steps' mode)
set -euo pipefail
a=$1
b=$2
steps=${3:-1000}
repeats=${4:-7}
work=${5:-/tmp/aniso-dem-ovoid}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for alpha in 1.0 0.5; do
  [[ -f $work/alpha_$alpha/prepared.h5 ]] || { echo "compare.sh: no $work/alpha_$alpha/prepared.h5: run run.sh first" >&2; exit 2; }
done
results=$work/compare.txt
: >"$results"
for _ in $(seq "$repeats"); do
  for alpha in 0.5 1.0; do
    for bin in "$a" "$b"; do
      rate=$("$bin" "$work/alpha_$alpha/prepared.h5" "$steps" 1 "${MODE:-load}" | sed 's/.*: \([0-9.e+]*\) particle-steps.*/\1/')
      echo "$bin $alpha $rate" >>"$results"
    done
  done
done
if [[ ${COUNT_INSTRUCTIONS:-0} == 1 ]]; then
  for bin in "$a" "$b"; do
    for alpha in 0.5 1.0; do
      count() {
        valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$work/alpha_$alpha/prepared.h5" "$1" 1 2>&1 |
          sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
      }
      echo "instructions $bin $alpha $((($(count 100) - $(count 0)) / 100))" >>"$results"
    done
  done
fi
/usr/bin/python3 - "$results" <<'PY'
import collections, statistics, sys
rates, instructions = collections.defaultdict(list), {}
for line in open(sys.argv[1]):
    fields = line.split()
    if fields[0] == "instructions":
        instructions[(fields[1], fields[2])] = int(fields[3])
    else:
        rates[(fields[0], fields[1])].append(float(fields[2]))
spheres = statistics.median([r for (bin, alpha), v in rates.items() if alpha == "1.0" for r in v])
for (bin, alpha), v in sorted(rates.items()):
    print(f"{bin} alpha {alpha}: median {statistics.median(v):.4g} particle-steps/s, fastest {max(v):.4g} ({len(v)} runs)")
for bin in sorted({bin for bin, _ in rates}):
    print(f"{bin}: ovoids cost {spheres / statistics.median(rates[(bin, '0.5')]):.2f}x the pooled sphere median {spheres:.4g}")
for (bin, alpha), n in sorted(instructions.items()):
    print(f"{bin} alpha {alpha}: {n / 1e6:.2f}e6 instructions per loading step")
PY
