#!/usr/bin/env bash
# DEMPLA/OVAL start files (Kuhn's D-files) in and out of aniso, and `consolidate`:
# - export -> import gives every sphere back at its position and size (exact) and the bare
#   LAMMPS import's contacts and p (the D-file has no contact forces);
# - --d50 rescales a unitless file (DEMPLA's samples: D50 = 1) to the same assembly in metres;
# - `consolidate` brings an imported assembly that lost its tangential forces to p0 and a
#   verified static state (a fixed-cell hold keeps p within 1e-3), the same bits on 1 and 2 ranks,
#   and `load` starts from it;
# - files aniso cannot represent are refused by name (exit 3), bad requests with exit 2, and
#   nothing is written or overwritten.
#
# usage: dempla_start_file.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
small_prepared_assembly "$build" dem

expect_exit 0 export_dfile "200 spheres in DEMPLA D-file" "$dem" export --input dem/prepared.h5 --format dempla \
  --output Dsmall
expect_exit 0 import_dfile "import of 'Dsmall' (dempla): 200 spheres" "$dem" import --input Dsmall \
  --format dempla --output from_dfile.h5
expect_exit 0 export_lammps "200 spheres" "$dem" export --input dem/prepared.h5 --output a.data
expect_exit 0 import_lammps "contacts by aniso" "$dem" import --input a.data --output from_lammps.h5

# The same assembly without units and at 3.7 times D50 = 1, as DEMPLA's samples are.
/usr/bin/python3 - Dsmall Dunitless <<'PY'
import sys
import numpy as np
lines = open(sys.argv[1]).read().splitlines()
rows = np.array([[float(w) for w in line.split()] for line in lines[3:]])
r = rows[:, 0]
order = np.argsort(r)
cumulative = np.cumsum(r[order] ** 3)
d50 = 2 * r[order][np.searchsorted(cumulative, 0.5 * cumulative[-1])]
scale = 3.7 / d50
lengths = [float(w) * scale for w in lines[1].split()[1:]]
with open(sys.argv[2], "w") as out:
    out.write(f"4\n{len(rows):6d}" + "".join(f"{v:25.17e}" for v in lengths) + "\n")
    out.write("      " + "".join(f"{0.0:25.17e}" for _ in range(3)) + "\n")
    for row in rows * scale:
        out.write("".join(f"{v:25.17e}" for v in row) + "\n")
PY
d50=$(/usr/bin/python3 - <<'PY'
import h5py
import numpy as np
d = np.sort(h5py.File("dem/prepared.h5", "r")["particles/diameter"][:])
cumulative = np.cumsum(d**3)
print(repr(d[np.searchsorted(cumulative, 0.5 * cumulative[-1])]))
PY
)
expect_exit 0 import_scaled "D50 $(printf %.6g "$d50") m" "$dem" import --input Dunitless --format dempla \
  --d50 "$d50" --output scaled.h5

/usr/bin/python3 - <<'PY' || status=1
import re
import h5py
import numpy as np

def logged_p(name):
    return float(re.search(r"p = ([0-9.e+-]+) Pa", open(name).read()).group(1))

with h5py.File("dem/prepared.h5", "r") as a, h5py.File("from_dfile.h5", "r") as b, \
        h5py.File("from_lammps.h5", "r") as c, h5py.File("scaled.h5", "r") as s:
    source = b["particles/source_id"][:]
    moved = np.abs(b["particles/position"][:] - a["particles/position"][:][source - 1]).max()
    sizes = np.abs(b["particles/diameter"][:] - a["particles/diameter"][:][source - 1]).max()
    scaled = np.abs(s["particles/position"][:] / b["particles/position"][:] - 1).max()
    scaled_cell = np.abs(s["cell/lengths"][:] / a["cell/lengths"][:] - 1).max()
    contacts = (len(b["contacts/overlap"]), len(c["contacts/overlap"]))
    overlaps = np.array_equal(np.sort(b["contacts/overlap"][:]), np.sort(c["contacts/overlap"][:]))
checks = {
    "every sphere came back at its position (exact)": moved == 0.0,
    "every sphere came back with its diameter (exact)": sizes == 0.0,
    f"the same contacts as the LAMMPS import ({contacts[0]} and {contacts[1]})": contacts[0] == contacts[1],
    "the LAMMPS import's overlaps (exact)": overlaps,
    # The D-file has no velocities: the LAMMPS import's kinetic stress (kinetic/elastic 2e-5) differs.
    "the LAMMPS import's p to 1e-6": abs(logged_p("import_dfile.log") / logged_p("import_lammps.log") - 1) <= 1e-6,
    f"--d50 gives the positions back to 1e-12 (largest relative difference {scaled:.1e})": scaled <= 1e-12,
    f"--d50 gives the cell back to 1e-12 ({scaled_cell:.1e})": scaled_cell <= 1e-12,
}
for name, ok in checks.items():
    print(("ok: " if ok else "FAIL: ") + name)
raise SystemExit(0 if all(checks.values()) else 1)
PY

# consolidate: the bare import has lost its tangential forces; consolidation makes it static at p0.
p0=80e3
expect_exit 0 consolidate "consolidate of 'from_dfile.h5'" "$dem" consolidate --input from_dfile.h5 \
  --output consolidated.h5 --set dem.prepare.confining_pressure=$p0
mpiexec --oversubscribe -n 2 "$dem" consolidate --input from_dfile.h5 --output consolidated_np2.h5 \
  --set dem.prepare.confining_pressure=$p0 --log-level warn
for group in /particles /contacts /cell; do
  h5diff consolidated.h5 consolidated_np2.h5 "$group" "$group" >diff.txt ||
    { echo "FAIL: 2 ranks consolidated to another $group than 1 rank:"; head -5 diff.txt; status=1; }
done
grep -Eq "p [0-9.e+]+ -> (79|80)[0-9.]* Pa" consolidate.log ||
  { echo "FAIL: consolidate did not reach p0 = $p0 Pa:"; grep consolidate consolidate.log; status=1; }
expect_exit 0 hold_consolidated "hold of" "$dem" hold --input consolidated.h5 --steps 20000 --max-drift 1e-3
expect_exit 0 load_consolidated "load done" "$dem" load --input consolidated.h5 --set dem.output_dir=load \
  --set dem.load.final_strain=2e-4 --set dem.load.checkpoint_strains=[2e-4] --set dem.load.mean_stress=$p0

# Refusals, with nothing written.
refuse() { # NAME PATTERN EXIT FILE [OPTIONS...]
  local name=$1 pattern=$2 code=$3 file=$4
  shift 4
  expect_exit "$code" "$name" "$pattern" "$dem" import --input "$file" --format dempla --output "$name.h5" "$@"
  [ ! -e "$name.h5" ] || { echo "FAIL: $name: a checkpoint was written"; status=1; }
}
sed '1s/^4$/5/' Dsmall >Dovoid
refuse ovoid "line 1: shape code 5: aniso imports DEMPLA's spheres (code 4) only" 3 Dovoid
awk 'NR == 3 { $2 = "1.0E-05" } { print }' Dsmall >Dsheared
refuse sheared "line 3: cell offset 1.0E-05: aniso's periodic cell is rectangular" 3 Dsheared
head -n 100 Dsmall >Dshort
refuse short "97 spheres, the header says 200" 3 Dshort
awk 'NR == 10 { $1 = "-0.1" } { print }' Dsmall >Dnegative
refuse negative "line 10: radius -0.1, expected > 0" 3 Dnegative
refuse both "give one or the other" 2 Dsmall --d50 1e-4 --contacts a.data
cp consolidated.h5 kept.h5
expect_exit 2 consolidate_exists "exists: give a new file" "$dem" consolidate --input from_dfile.h5 \
  --output consolidated.h5
cmp -s consolidated.h5 kept.h5 || { echo "FAIL: consolidate overwrote its --output"; status=1; }

if [ "$status" = 0 ]; then echo "dempla_start_file: all checks passed"; fi
exit "$status"
