#!/bin/bash
# The voxel benchmark of docs/performance.md in one run:
#  1. a checkpoint alone at 20 voxels per d50: aniso (bench_voxel, 1 thread, median of 5) and the
#     scipy.ndimage / scikit-image periodic openings of the same image at the same sizes
#     (bench_voxel_peer.py), which also compares every kept-voxel count with aniso's;
#  2. the checkpoint tiled to about 60 million voxels at 20 voxels per d50, on 1 and 2 threads.
# usage: tests/perf/bench_voxel.sh BUILD_DIR CHECKPOINT.h5 OUT_DIR [TILES="6 6 3"]
set -euo pipefail
build=$1 checkpoint=$2 out=$3 tiles=${4:-"6 6 3"}
[[ -x $build/tests/perf/bench_voxel ]] || { echo "missing $build/tests/perf/bench_voxel: cmake --build $build --target benchmarks" >&2; exit 2; }
mkdir -p "$out"
stem=$(basename "$checkpoint" .h5)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "== $(date -u +%FT%TZ) $(uname -n), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
OMP_NUM_THREADS=1 "$build/voxel/aniso-voxel" --input "$checkpoint" --set "voxel.output_dir='$out'" --log-level warn
"$build/tests/perf/bench_voxel" "$checkpoint" --threads 1 --repeats 5
/usr/bin/python3 "$(dirname "$0")/bench_voxel_peer.py" "$out/image_$stem.h5" "$out/voids_$stem.h5" --skimage \
  | grep -v '^  '
for threads in 2 1; do
  # shellcheck disable=SC2086
  /usr/bin/time -f "process: %e s wall, %U s user, peak RSS %M KB" \
    "$build/tests/perf/bench_voxel" "$checkpoint" --tiles $tiles --threads "$threads" --repeats 1
done
