#!/usr/bin/env bash
# DEMPLA/OVAL start files (Kuhn's D-files) in and out of aniso, and `consolidate`:
# - export -> import gives every sphere back at its position and size (exact) and the bare
#   LAMMPS import's contacts and p (the D-file has no contact forces);
# - --d50 rescales a unitless file (DEMPLA's samples: D50 = 1) to the same assembly in metres;
# - ovoids (shape 5): an ovoid D-file comes in with its axes and aspect ratio (rows wrapped over
#   two lines as DEMPLA's samples have them read the same) and goes out and in again unchanged;
#   dem.material.hertz_radius = mean_semi_axis (DEMPLA 0.2.5's a (2 + alpha) / 3) scales p of the
#   same overlaps by exactly sqrt((2 + alpha) / 3) against halfwidth;
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

expect_exit 0 export_dfile "200 particles in DEMPLA D-file" "$dem" export --input dem/prepared.h5 --format dempla \
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

# Ovoids: the 200 spheres as ovoids of aspect ratio 0.8 with random axes, in a cell 1% smaller so
# that they touch; the D-file's rows wrapped after 4 values as in DEMPLA's StartFiles/DOblate_1800.
/usr/bin/python3 - Dsmall Dovoids Dovoids_wrapped <<'PY'
import sys
import numpy as np
lines = open(sys.argv[1]).read().splitlines()
rows = np.array([[float(w) for w in line.split()] for line in lines[3:]])
rng = np.random.default_rng(5)
axis = rng.normal(size=(len(rows), 3))
axis /= np.linalg.norm(axis, axis=1)[:, None]
g1, g2 = np.degrees(np.arccos(axis[:, 2])), np.degrees(np.arctan2(axis[:, 1], axis[:, 0]))
shrink = 0.99
lengths = [float(w) * shrink for w in lines[1].split()[1:]]
head = f"5\n{len(rows):6d}" + "".join(f"{v:25.17e}" for v in lengths) + "\n"
head += "      " + "".join(f"{0.0:25.17e}" for _ in range(3)) + "\n" + f"{45.0:25.17e}\n"
values = [[r[0], 0.8, *(r[1:] * shrink), a, b] for r, a, b in zip(rows, g1, g2)]
with open(sys.argv[2], "w") as out:
    out.write(head + "".join("".join(f"{v:25.17e}" for v in row) + "\n" for row in values))
with open(sys.argv[3], "w") as out:
    out.write(head + "".join("".join(f"{v:25.17e}" for v in row[:4]) + "\n" + "".join(f"{v:25.17e}" for v in row[4:])
                             + "\n" for row in values))
PY
expect_exit 0 import_ovoids "200 ovoids of aspect ratio 0.8" "$dem" import --input Dovoids --format dempla \
  --output ovoids.h5
expect_exit 0 import_ovoids_wrapped "200 ovoids" "$dem" import --input Dovoids_wrapped --format dempla \
  --output ovoids_wrapped.h5
expect_exit 0 import_ovoids_dempla_hertz "200 ovoids" "$dem" import --input Dovoids --format dempla \
  --output ovoids_mean_axis.h5 --set dem.material.hertz_radius=mean_semi_axis
expect_exit 0 export_ovoids "200 particles in DEMPLA D-file" "$dem" export --input ovoids.h5 --format dempla \
  --output Dovoids_again
expect_exit 0 import_ovoids_again "200 ovoids" "$dem" import --input Dovoids_again --format dempla \
  --output ovoids_again.h5
# Read back, the mean_semi_axis checkpoint restores its contacts' forces with that radius.
expect_exit 0 hold_ovoids_dempla_hertz "hold of" "$dem" hold --input ovoids_mean_axis.h5 --steps 1
for group in /particles /contacts /cell; do
  h5diff ovoids.h5 ovoids_wrapped.h5 "$group" "$group" >diff.txt ||
    { echo "FAIL: the wrapped rows gave another $group:"; head -5 diff.txt; status=1; }
done
/usr/bin/python3 - <<'PY' || status=1
import re
import h5py
import numpy as np

def logged_p(name):
    return float(re.search(r"p = ([0-9.e+-]+) Pa", open(name).read()).group(1))

def axes(f):
    w, x, y, z = f["particles/orientation"][:].T  # body z turned into the world frame
    return np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=1)

lines = open("Dovoids").read().splitlines()
rows = np.array([[float(w) for w in line.split()] for line in lines[4:]])
g1, g2 = np.radians(rows[:, 5]), np.radians(rows[:, 6])
given = np.stack([np.sin(g1) * np.cos(g2), np.sin(g1) * np.sin(g2), np.cos(g1)], axis=1)
with h5py.File("ovoids.h5", "r") as a, h5py.File("ovoids_again.h5", "r") as b:
    source = a["particles/source_id"][:] - 1
    axis_error = np.abs(np.abs((axes(a) * given[source]).sum(axis=1)) - 1).max()
    again = b["particles/source_id"][:] - 1
    # Dovoids_again's rows are ovoids.h5's particles in id order: ovoids_again's source ids name them.
    moved = np.abs(b["particles/position"][:] - a["particles/position"][:][again]).max()
    again_axes = np.abs(np.abs((axes(b) * axes(a)[again]).sum(axis=1)) - 1).max()
    aspect = set(a["particles/aspect_ratio"][:])
    contacts = (len(a["contacts/overlap"]), len(b["contacts/overlap"]))
ratio = logged_p("import_ovoids_dempla_hertz.log") / logged_p("import_ovoids.log")
restored = float(re.search(r"p ([0-9.e+-]+) -> ", open("hold_ovoids_dempla_hertz.log").read()).group(1))
checks = {
    f"the D-file's axes to 1e-12 (largest 1 - |cos| {axis_error:.1e})": axis_error <= 1e-12,
    f"aspect ratio 0.8 for every particle ({sorted(aspect)})": aspect == {0.8},
    f"contacts among the ovoids ({contacts[0]})": contacts[0] >= 20,
    f"export -> import: the positions (exact: {moved:.1e}), axes to 1e-12 ({again_axes:.1e}), contacts "
    f"({contacts[1]})": moved == 0.0 and again_axes <= 1e-12 and contacts[0] == contacts[1],
    # to 1e-8: the logs print p to 9 digits
    f"mean_semi_axis against halfwidth: p ratio {ratio:.10f}, sqrt(2.8 / 3) = {np.sqrt(2.8 / 3):.10f} (1e-8)":
    abs(ratio - np.sqrt(2.8 / 3)) <= 1e-8,
    # to 1e-5: the hold prints p to 6 digits
    f"restored mean_semi_axis checkpoint: p {restored:g} Pa as imported (1e-5)":
    abs(restored / logged_p("import_ovoids_dempla_hertz.log") - 1) <= 1e-5,
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
sed '1s/^4$/6/' Dsmall >Dclusters
refuse clusters "line 1: shape code 6: aniso imports DEMPLA's spheres (code 4) and ovoids (5)" 3 Dclusters
awk 'NR == 10 { $2 = "0.7" } { print }' Dovoids >Dmixed
refuse mixed "line 10: aspect ratio 0.69999999999999996 where the first particle has 0.80000000000000004: aniso holds one aspect ratio per assembly" 3 Dmixed
awk 'NR == 4 { $1 = "78.0" } { print }' Dovoids >Dsplice
refuse splice "splice angle 78 degrees, expected between 0 and 2 atan(aspect ratio) = 77.3196 degrees" 2 Dsplice
awk 'NR == 3 { $2 = "1.0E-05" } { print }' Dsmall >Dsheared
refuse sheared "line 3: cell offset 1.0E-05: aniso's periodic cell is rectangular" 3 Dsheared
head -n 100 Dsmall >Dshort
refuse short "97 particles, the header says 200" 3 Dshort
awk 'NR == 10 { $1 = "-0.1" } { print }' Dsmall >Dnegative
refuse negative "line 10: radius -0.1, expected > 0" 3 Dnegative
refuse both "give one or the other" 2 Dsmall --d50 1e-4 --contacts a.data
cp consolidated.h5 kept.h5
expect_exit 2 consolidate_exists "exists: give a new file" "$dem" consolidate --input from_dfile.h5 \
  --output consolidated.h5
cmp -s consolidated.h5 kept.h5 || { echo "FAIL: consolidate overwrote its --output"; status=1; }

if [ "$status" = 0 ]; then echo "dempla_start_file: all checks passed"; fi
exit "$status"
