#!/usr/bin/env bash
# A bad particle row (a mass or an aspect ratio no simulation can start from) is refused with
# exit 3 and the same message naming the file, the dataset and the row, on 1 rank and on 2,
# where the distributed read gives each rank its own rows to check: the rank that holds the row
# finds it, and every rank stops with its message (naming that rank), none waits for the others.
#
# usage: bad_particle_rows.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
dem=$build/dem/aniso-dem
"$dem" prepare --set dem.particles.count=400 --set dem.seed=6 --set dem.particles.diameter_min=1.4e-4 \
  --set dem.particles.diameter_max=1.8e-4 --set dem.particles.d50=1.6e-4 --set dem.prepare.cycles=1 \
  --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 \
  --set dem.output_dir="$work" --log-level warn
/usr/bin/python3 - "$work/prepared.h5" <<'PY'
import shutil, sys
import h5py
source = sys.argv[1]
# A negative mass (the reader's own check) and aspect ratios in (0, 1] that no shape supports
# (dem.particles.aspect_ratio's range, from_checkpoint's check), in the first and the last slab.
for name, dataset, row, value in (("last_mass", "mass", -1, -1.0), ("first_aspect", "aspect_ratio", 0, 0.1),
                                  ("last_aspect", "aspect_ratio", -1, 0.1)):
    target = source.replace("prepared.h5", f"{name}.h5")
    shutil.copy(source, target)
    with h5py.File(target, "r+") as f:
        data = f["particles"][dataset]
        data[row if row >= 0 else data.shape[0] + row] = value
PY
status=0
# Every rank prints the message (one write each, so it stays whole when their lines interleave).
expect() {
  local ranks=$1 file=$2 message=$3
  set +e
  mpiexec --oversubscribe -n "$ranks" "$dem" hold --input "$work/$file" --steps 1 >"$work/$file.np$ranks.log" 2>&1
  local code=$?
  set -e
  local found
  found=$(grep -o -F -- "$message" "$work/$file.np$ranks.log" | wc -l)
  if [ "$code" != 3 ] || [ "$found" != "$ranks" ]; then
    echo "FAIL: $ranks rank(s), $file: exit $code (expected 3), '$message' printed $found times (expected $ranks):"
    cat "$work/$file.np$ranks.log"
    status=1
  fi
}
mass="$work/last_mass.h5: /particles/mass: value -1 at row 399, expected > 0"
first="$work/first_aspect.h5: /particles/aspect_ratio: row 0 (particle id 0): 0.1, expected (0.2, 1]"
last="$work/last_aspect.h5: /particles/aspect_ratio: row 399 (particle id 399): 0.1, expected (0.2, 1]"
for file in last_mass first_aspect last_aspect; do
  case $file in last_mass) message=$mass rank=1 ;; first_aspect) message=$first rank=0 ;; *) message=$last rank=1 ;; esac
  expect 1 "$file.h5" "$message"
  expect 2 "$file.h5" "$message (found on rank $rank)"
done
mpiexec --oversubscribe -n 2 "$dem" hold --input "$work/prepared.h5" --steps 1 --log-level warn ||
  { echo "FAIL: the untouched file is refused on 2 ranks"; status=1; }
[ "$status" = 0 ] && echo "bad particle rows refused with exit 3 and the row named, on 1 and 2 ranks"
exit "$status"
