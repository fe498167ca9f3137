#!/bin/bash
# LBM throughput of aniso (bench_lbm) against Palabos (palabos_bench) on the same image, in the
# same session, at 1 and 2 ranks, with the triad bandwidth measured by bench_lbm.
#
# usage: run.sh [IMAGE.h5] [STEPS=100] [REPEATS=5] [WORKDIR=/tmp/aniso-lbm-peer]
#   IMAGE.h5: a voxel image; default a random packing of spheres of diameter 20 voxels (20 voxels
#   per D50) at solid fraction 0.6 in a 128^3 box, made by make_lbm_image.
# environment: ANISO_BUILD (build folder with bench_lbm and make_lbm_image; default /work/build),
#              PEER_RANKS (default "1 2"), PRECISION (default double),
#              ANISO_BASELINE (optional second build folder, e.g. an older commit: its bench_lbm runs right
#              after aniso's, interleaved, for an A/B of two versions in the same session)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
image=${1:-}
steps=${2:-100}
repeats=${3:-5}
work=${4:-/tmp/aniso-lbm-peer}
build=${ANISO_BUILD:-/work/build}
[[ -x $build/tests/perf/bench_lbm ]] || { echo "missing $build/tests/perf/bench_lbm: cmake --build $build --target benchmarks" >&2; exit 2; }
ranks_list=${PEER_RANKS:-"1 2"}
precision=${PRECISION:-double}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
mkdir -p "$work"
[ -x "$work/palabos_bench" ] || "$here/build.sh" "$work" > /dev/null
if [ -z "$image" ]; then
  image=$work/packing128.h5
  [ -f "$image" ] || "$build/tests/lbm/make_lbm_image" random "$image" --side 128 --radius 10 --solid-fraction 0.6
fi
read -r n1 n2 n3 < <(/usr/bin/python3 "$here/image_to_palabos.py" "$image" "$work/geometry.txt")
echo "image $image: ${n1}x${n2}x${n3}; $(date -u +%FT%TZ); $(lscpu | sed -n 's/^Model name: *//p')"
for ranks in $ranks_list; do
  mpiexec --oversubscribe -n "$ranks" "$build/tests/perf/bench_lbm" --image "$image" --steps "$steps" \
    --repeats "$repeats" --precision "$precision"
  if [ -n "${ANISO_BASELINE:-}" ]; then
    echo -n "baseline $ANISO_BASELINE: "
    mpiexec --oversubscribe -n "$ranks" "$ANISO_BASELINE/tests/perf/bench_lbm" --image "$image" --steps "$steps" \
      --repeats "$repeats" --precision "$precision"
  fi
  mpiexec --oversubscribe -n "$ranks" "$work/palabos_bench" "$work/geometry.txt" "$n1" "$n2" "$n3" "$steps" \
    "$repeats" "$precision"
done
