#!/usr/bin/env bash
# Every array aniso writes carries HDF5's Fletcher32 checksum: one flipped bit in a checkpoint's
# /particles/position or an image's /image/phase makes the stage that reads it stop with exit 3
# (file error) naming the dataset and the failed checksum, instead of using a wrong value.
#
# usage: bit_flip.sh BUILD_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/../tools/cli_lib.sh"
build=$1
enter_fresh_folder "$2"
small_checkpoint_and_image "$build"
image=voxel/image_prepared.h5
status=0

# flip COPY DATASET: flips one bit in the middle of DATASET's first stored chunk, in place.
flip() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py
path, name = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    chunk = f[name].id.get_chunk_info(0)
    offset = chunk.byte_offset + chunk.size // 2
with open(path, "r+b") as f:
    f.seek(offset)
    byte = f.read(1)[0]
    f.seek(offset)
    f.write(bytes([byte ^ 0x10]))
PY
}

# expect NAME DATASET COMMAND...: exit 3 with the dataset and the checksum named.
expect() {
  local name=$1 dataset=$2
  shift 2
  expect_exit 3 "$name" "error (file error): .*$dataset: the data fails its Fletcher32 checksum" "$@"
}

cp dem/prepared.h5 flipped.h5
flip flipped.h5 particles/position
expect fabric /particles/position "$build/fabric/aniso-fabric" --input flipped.h5 --output fabric.h5
expect load /particles/position "$build/dem/aniso-dem" load --input flipped.h5 --set dem.output_dir=load
cp "$image" flipped_image.h5
flip flipped_image.h5 image/phase
expect lbm /image/phase "$build/lbm/aniso-lbm" --input flipped_image.h5 --set lbm.output_dir=lbm
# The untouched files still read: the failures above are the flipped bit's.
"$build/fabric/aniso-fabric" --input dem/prepared.h5 --output fabric.h5 --log-level warn ||
  { echo "FAIL: the intact checkpoint does not read"; status=1; }
[ "$status" = 0 ] && echo "bit flips: exit 3 naming the dataset's failed checksum in fabric, load and lbm"
exit "$status"
