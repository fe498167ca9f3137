#!/usr/bin/env bash
# A problem larger than the memory this process may use is refused before it is allocated, with
# exit 2 and what was asked for (it ended in "internal error: std::bad_alloc", exit 1): DEM
# particles, a voxel image at a high resolution and an image file whose dimensions are huge.
# The limit is set with ulimit -v, which common/memory.cpp reads as a job's memory limit would be.
#
# usage: memory_limits.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/../tools/cli_lib.sh"
build=$1
enter_fresh_folder "$2"
small_checkpoint_and_image "$build"
# An image file of 2000^3 voxels that are never stored (chunks left at the fill value): small on
# disk, 7.5 GiB to read.
/usr/bin/python3 - voxel/image_prepared.h5 huge.h5 <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r") as source, h5py.File(sys.argv[2], "w") as target:
    for key, value in source.attrs.items():
        target.attrs[key] = value
    source.copy("provenance", target)
    group = target.create_group("image")
    phase = group.create_dataset("phase", shape=(2000, 2000, 2000), dtype="u1", chunks=(64, 64, 64))
    for key, value in source["image/phase"].attrs.items():
        phase.attrs[key] = value
PY
status=0

# expect NAME PATTERN COMMAND...: exit 2 with PATTERN, under a 3 GiB address-space limit.
expect() {
  local name=$1 pattern=$2
  shift 2
  expect_exit 2 "$name" "error (bad input): $pattern.*more than the 3 GiB this process may use" \
    bash -c 'ulimit -v 3145728 && exec "$@"' limited "$@"
}

expect dem "dem: 1000000000 particles on 1 rank(s) (at least 512 bytes each): about 477 GiB needed" \
  "$build/dem/aniso-dem" prepare --set dem.particles.count=1000000000 --set dem.output_dir=big
expect voxel "voxel: .* voxels at resolution 200 (per rank): about" \
  "$build/voxel/aniso-voxel" --input dem/prepared.h5 --set voxel.resolution=200 --set voxel.output_dir=v200
expect image "huge.h5: the 2000 x 2000 x 2000 voxel image: about 7.45 GiB needed" \
  "$build/lbm/aniso-lbm" --input huge.h5 --set lbm.output_dir=lbm
[ "$status" = 0 ] && echo "memory limits: particles, resolution and image dimensions refused with exit 2 and the size asked for"
exit "$status"
