#!/usr/bin/env bash
# Restored contacts must match the stored positions: a checkpoint whose /contacts
# overlap was edited (x10), or from which one contact row was dropped, is refused with exit 3
# naming the file and the pair, for spheres and for ovoids; the untouched file is accepted.
#
# usage: tampered_contacts.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
dem=$build/dem/aniso-dem
status=0
for shape in 1 0.5; do
  out="$work/alpha$shape"
  "$dem" prepare --set dem.particles.count=400 --set dem.seed=6 --set dem.particles.diameter_min=1.4e-4 \
    --set dem.particles.diameter_max=1.8e-4 --set dem.particles.d50=1.6e-4 --set dem.prepare.cycles=1 \
    --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 \
    --set dem.prepare.initial_solid_fraction=0.35 --set dem.particles.aspect_ratio="$shape" \
    --set dem.output_dir="$out" --log-level warn
  /usr/bin/python3 - "$out/prepared.h5" <<'PY'
import shutil, sys
import h5py, numpy as np
source = sys.argv[1]
for name in ("overlap_x10", "row_dropped"):
    target = source.replace("prepared.h5", f"{name}.h5")
    shutil.copy(source, target)
    with h5py.File(target, "r+") as f:
        contacts = f["contacts"]
        k = int(np.argmax(contacts["overlap"][...]))  # the deepest contact: a change no tolerance hides
        if name == "overlap_x10":
            contacts["overlap"][k] = 10 * contacts["overlap"][k]
        else:
            for key in list(contacts):
                data = np.delete(contacts[key][...], k, axis=0)
                attributes = dict(contacts[key].attrs)
                del contacts[key]
                contacts.create_dataset(key, data=data)
                contacts[key].attrs.update(attributes)
PY
  expect() {
    local file=$1 pattern=$2
    set +e
    "$dem" hold --input "$out/$file" --steps 1 >"$out/$file.log" 2>&1
    local code=$?
    set -e
    if [ "$code" != 3 ] || ! grep -q "$pattern" "$out/$file.log"; then
      echo "FAIL: alpha $shape, $file: exit $code (expected 3) or no '$pattern':"; cat "$out/$file.log"; status=1
    fi
  }
  expect overlap_x10.h5 "stores an overlap of .* where the stored positions give"
  expect row_dropped.h5 "but /contacts has no row for them"
  "$dem" hold --input "$out/prepared.h5" --steps 1 --log-level warn || { echo "FAIL: alpha $shape: untouched file refused"; status=1; }
done
[ "$status" = 0 ] && echo "tampered contacts refused with exit 3 for spheres and ovoids; untouched files accepted"
exit "$status"
