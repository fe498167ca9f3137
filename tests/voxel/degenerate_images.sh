#!/usr/bin/env bash
# aniso-voxel on a checkpoint whose image is all void (particles shrunk below a voxel) stops with
# exit 4 and says so, writing no result; it once wrote NaN and inf medians with exit 0. Particles
# swollen to fill the cell (an all-solid image) overlap far beyond the explosion limit: the
# checkpoint reader refuses them first (exit 3, naming a pair; docs/user-guide.md "Impossible and
# degenerate states").
#
# usage: degenerate_images.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
"$build/dem/aniso-dem" prepare --set dem.particles.count=200 --set dem.seed=2 --set dem.prepare.cycles=1 \
  --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 \
  --set dem.prepare.initial_solid_fraction=0.35 --set dem.output_dir="$work" --log-level warn
/usr/bin/python3 - "$work" <<'PY'
import shutil, sys
import h5py
work = sys.argv[1]
for name, factor in (("swollen", 4.0), ("shrunk", 1e-3)):
    shutil.copy(f"{work}/prepared.h5", f"{work}/{name}.h5")
    with h5py.File(f"{work}/{name}.h5", "r+") as f:
        f["particles/diameter"][...] = factor * f["particles/diameter"][...]
PY
status=0
for case in "swollen:3:overlap by [0-9.]* of the smaller one's radius" \
            "shrunk:4:is all void (the void morphology is undefined)"; do
  name=${case%%:*} rest=${case#*:}
  expected_code=${rest%%:*} expected=${rest#*:}
  set +e
  "$build/voxel/aniso-voxel" --input "$work/$name.h5" --set voxel.output_dir="$work/out_$name" \
    --set voxel.resolution=6 >"$work/$name.log" 2>&1
  code=$?
  set -e
  if [ "$code" != "$expected_code" ] || ! grep -q "$expected" "$work/$name.log"; then
    echo "FAIL: $name: exit $code (expected $expected_code) or no '$expected':"; cat "$work/$name.log"; status=1
  elif ls "$work/out_$name"/voids_* >/dev/null 2>&1; then
    echo "FAIL: $name: results were written"; status=1
  fi
done
[ "$status" = 0 ] && echo "all-void image: exit 4 naming the case; swollen particles refused on reading; no results written"
exit "$status"
