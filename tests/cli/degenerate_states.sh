#!/usr/bin/env bash
# States no DEM run can write, and inputs a stage cannot use, are refused by every stage that
# reads them, before any work, with the exit code of the rule in docs/user-guide.md ("Degenerate
# states"): exit 3 for a checkpoint without particles, with two particles at one position, with a
# pair overlapping beyond the explosion limit, or whose particle rows claim 1e12 particles (a
# damaged file, not "out of memory"); exit 2 for a checkpoint given twice to `aniso-fabric series`
# (before anything is measured) and a text export named .xmf. A valid state without contacts (a
# single particle among them) is measured, its undefined ratios NaN, with a stored warning.
#
# usage: degenerate_states.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
status=0
source "$(dirname "$0")/../tools/cli_lib.sh"
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem fabric=$build/fabric/aniso-fabric voxel=$build/voxel/aniso-voxel
small_prepared_assembly "$build" dem
"$dem" load --set dem.load.final_strain=0.002 --set 'dem.load.checkpoint_strains=[0.001, 0.002]' \
  --set dem.equilibrium.at_checkpoints=false --set dem.output_dir=dem --input dem/prepared.h5 --log-level warn

/usr/bin/python3 - dem/load_001.h5 <<'PY'
import shutil, sys
import h5py, numpy as np
source = sys.argv[1]

def keep_rows(f, group, rows):
    for key in list(f[group]):
        data, attributes = f[group][key][...][rows], dict(f[group][key].attrs)
        del f[group][key]
        f[group].create_dataset(key, data=data)
        f[group][key].attrs.update(attributes)

def variant(name, edit):
    shutil.copy(source, name + ".h5")
    with h5py.File(name + ".h5", "r+") as f:
        edit(f)

def move_particle_1(f, offset):
    # particle 1 placed at `offset` from particle 0, its contacts (and 0's) dropped
    position, diameter = f["particles/position"][...], f["particles/diameter"][...]
    position[1] = (position[0] + offset * 0.5 * (diameter[0] + diameter[1])) % f["cell/lengths"][...]
    f["particles/position"][...] = position
    pairs = f["contacts/particles"][...]
    keep_rows(f, "contacts", ~np.isin(pairs, [0, 1]).any(axis=1))

def claim_1e12(f):
    ids = f["particles/id"][...]
    del f["particles/id"]
    claimed = f["particles"].create_dataset("id", shape=(10**12,), maxshape=(None,), chunks=(1024,), dtype="u8")
    claimed[: len(ids)] = ids

variant("empty", lambda f: (keep_rows(f, "particles", slice(0, 0)), keep_rows(f, "contacts", slice(0, 0))))
variant("single", lambda f: (keep_rows(f, "particles", slice(0, 1)), keep_rows(f, "contacts", slice(0, 0))))
variant("coincident", lambda f: move_particle_1(f, np.zeros(3)))
variant("deep", lambda f: move_particle_1(f, np.array([0.5, 0.0, 0.0])))
variant("claims_1e12", claim_1e12)
variant("no_contacts", lambda f: keep_rows(f, "contacts", slice(0, 0)))
PY
# The contacts of no_contacts.h5 must agree with its positions for the DEM, not for fabric: it is
# a fabric-only state (the DEM would rebuild them).

# expect_everywhere CODE PATTERN FILE: every stage refuses FILE with CODE and PATTERN.
expect_everywhere() {
  local code=$1 pattern=$2 file=$3 stem=${3%.h5}
  expect_exit "$code" "load_$stem" "$pattern" "$dem" load --input "$file" --set dem.output_dir="load_$stem"
  expect_exit "$code" "hold_$stem" "$pattern" "$dem" hold --input "$file" --steps 10
  expect_exit "$code" "fabric_$stem" "$pattern" "$fabric" --input "$file" --output "fabric_$stem.h5"
  expect_exit "$code" "voxel_$stem" "$pattern" "$voxel" --input "$file" --set voxel.output_dir="voxel_$stem"
  for made in "load_$stem/load_000.h5" "fabric_$stem.h5" "voxel_$stem"; do
    [ ! -e "$made" ] || { echo "FAIL: $made was written from the refused $file"; status=1; }
  done
}
expect_everywhere 3 "empty.h5: /particles: no particles" empty.h5
expect_everywhere 3 "particles 0 and 1 share the position" coincident.h5
expect_everywhere 3 "particles 0 and 1 overlap by [0-9.]* of the smaller one's radius .*explosion limit 0.05" deep.h5
expect_everywhere 3 "/particles/id: shape \[1000000000000\] claims 8e+12 bytes .*the file is damaged" claims_1e12.h5

# A single particle is a void space all the same: measured.
"$voxel" --input single.h5 --set voxel.output_dir=voxel_single --set voxel.resolution=6 --log-level warn ||
  { echo "FAIL: aniso-voxel refused a single particle"; status=1; }

# No contacts (a loose gas; a single particle): measured, NaN ratios, the warning logged and stored.
for state in no_contacts single; do
  "$fabric" --input $state.h5 --output fabric_$state.h5 >fabric_$state.log 2>&1 ||
    { echo "FAIL: aniso-fabric refused $state.h5"; cat fabric_$state.log; status=1; }
  grep -q "warning.*no contacts: the stress ratios" fabric_$state.log ||
    { echo "FAIL: no warning logged for $state.h5"; status=1; }
  h5dump -a /checkpoints/$state/warning fabric_$state.h5 | grep -q "no contacts" ||
    { echo "FAIL: no warning stored with the fabric of $state.h5"; status=1; }
done

# series: the same checkpoint twice is refused before anything is measured.
expect_exit 2 series_twice "checkpoint 'dem/load_001.h5' is given more than once" \
  "$fabric" series --input dem/load_000.h5 dem/load_001.h5 dem/load_001.h5 --output series.h5
if grep -q "c1 = " series_twice.log || [ -e series.h5 ]; then
  echo "FAIL: series measured or wrote before refusing a checkpoint given twice"
  status=1
fi

# export: the format follows an .xmf name; a text format under an .xmf name is refused; the log
# names the file's particles, not the configuration's default count.
"$dem" export --input dem/load_001.h5 --output state.xmf >export.log 2>&1
head -c 5 state.xmf | grep -q "<?xml" || { echo "FAIL: export to state.xmf did not write XDMF"; status=1; }
if grep -q "1000 particles" export.log; then
  echo "FAIL: export logged the configuration's particle count:"
  cat export.log
  status=1
fi
expect_exit 2 lammps_named_xmf "writes a text file, but --output 'data.xmf' is named as XDMF" \
  "$dem" export --input dem/load_001.h5 --format lammps --output data.xmf
[ ! -e data.xmf ] || { echo "FAIL: data.xmf written"; status=1; }

[ "$status" = 0 ] && echo "degenerate states: refused by every stage with their codes; no contacts measured with a warning"
exit "$status"
