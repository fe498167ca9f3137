#!/bin/bash
# DEM throughput of alpha = 0.5 ovoids against spheres in the same session: the same
# particle count and grading, each packing prepared by aniso-dem itself (one compaction
# cycle, a fast preparation rate: the benchmark needs a dense jammed state, not the
# paper's void ratio), then bench_dem_steps times biaxial loading steps from each,
# median of REPEATS runs, alternating the two so that machine noise hits both alike.
#
# usage: run.sh [COUNT=6400] [STEPS=1000] [REPEATS=5] [WORKDIR=/tmp/aniso-dem-ovoid]
# environment: ANISO_BUILD (default: the repository's build/), RANKS (default 1), MODE (load, the
#   default: biaxial loading steps with the servo; hold: a fixed cell, where a static packing's
#   apart pairs stay proven apart and the spheres run twice as fast, the ovoids not)
set -euo pipefail
count=${1:-6400}
steps=${2:-1000}
repeats=${3:-5}
work=${4:-/tmp/aniso-dem-ovoid}
here=$(cd "$(dirname "$0")" && pwd)
build=${ANISO_BUILD:-$here/../../../build}
[[ -x $build/tests/perf/bench_dem_steps ]] || { echo "missing $build/tests/perf/bench_dem_steps: cmake --build $build --target benchmarks" >&2; exit 2; }
ranks=${RANKS:-1}
mode=${MODE:-load}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$work"
for alpha in 1.0 0.5; do
  out=$work/alpha_$alpha
  if [[ ! -f $out/prepared.h5 ]]; then
    echo "preparing $count particles of aspect ratio $alpha in $out (once)" >&2
    "$build/dem/aniso-dem" prepare --set dem.particles.count="$count" --set dem.particles.aspect_ratio="$alpha" \
      --set dem.prepare.cycles=1 --set dem.prepare.inertial_number=0.05 --set dem.prepare.void_ratio_tolerance=1 \
      --set dem.prepare.initial_solid_fraction=0.35 --set dem.output_dir="$out" --log-level warn
  fi
done
: >"$work/results.txt" # this run's rates only
for repeat in $(seq "$repeats"); do
  for alpha in 1.0 0.5; do
    mpiexec -n "$ranks" "$build/tests/perf/bench_dem_steps" "$work/alpha_$alpha/prepared.h5" "$steps" 1 "$mode" |
      sed "s/^/alpha $alpha: /" | tee -a "$work/results.txt"
  done
done
/usr/bin/python3 - "$work/results.txt" <<'PY'
import re, statistics, sys
rates = {}
for line in open(sys.argv[1]):
    m = re.match(r"alpha (\S+): .* ([0-9.e+]+) particle-steps/s", line)
    if m:
        rates.setdefault(m.group(1), []).append(float(m.group(2)))
s, o = statistics.median(rates["1.0"]), statistics.median(rates["0.5"])
print(f"median particle-steps/s: spheres {s:.4g}, alpha 0.5 ovoids {o:.4g}; ovoids cost {s / o:.2f}x spheres "
      f"({len(rates['1.0'])} runs each)")
PY
