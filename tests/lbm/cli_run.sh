#!/bin/bash
# End-to-end checks of aniso-lbm on a small image: a run writes permeability_<stem>.h5 with the
# contract's datasets; --direction runs plus collect give the same tensor (a missing direction
# file is named, exit 3); a diverging run exits 4 (numerical failure), names the cause, and leaves the
# earlier result untouched; a run past its step limit exits 5; collect refuses direction files of
# different settings; an axis the pore space does not cross gets K = 0 and a warning naming it; a
# narrow throat is warned about with its width.
# usage: cli_run.sh ANISO_LBM MAKE_LBM_IMAGE MPIEXEC
set -euo pipefail
lbm=$1 make_image=$2 mpiexec=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$make_image" sphere_array "$work/cell.h5" --side 12 --solid-fraction 0.2 --voxel-size 1e-4
fail() { echo "cli_run.sh: $*" >&2; exit 1; }

"$mpiexec" --oversubscribe -n 2 "$lbm" --input "$work/cell.h5" --set lbm.output_dir="\"$work\"" \
  --set lbm.convergence.tolerance=1e-4 --set lbm.write_velocity=true > "$work/run.log" 2>&1 || { cat "$work/run.log"; fail "run failed"; }
result=$work/permeability_cell.h5
[ -f "$result" ] || fail "no $result"
[ -f "$work/velocity_cell.h5" ] && [ -f "$work/velocity_cell.xmf" ] || fail "no velocity field with XDMF sidecar"
header=$(h5dump -H "$result")
for name in 'DATASET "K"' 'DATASET "K_lattice"' 'ATTRIBUTE "method"' 'ATTRIBUTE "source_hash"'; do
  grep -q "$name" <<< "$header" || fail "$result lacks $name"
done
# K in m^2 = K_lattice * voxel_size^2, diagonal positive.
/usr/bin/python3 - "$result" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as f:
    g = f["permeability"]
    k, kl = g["K"][...], g["K_lattice"][...]
    assert g.attrs["method"] in (b"periodic_body_force", "periodic_body_force"), g.attrs["method"]
    assert np.allclose(k, kl * 1e-8, rtol=1e-12), (k, kl)
    assert (np.diag(kl) > 0).all(), kl
PY
checksum=$(md5sum < "$result")

# Job-array form: one direction per run, then collect; the same tensor to the last bit.
for d in 0 1 2; do
  "$lbm" --input "$work/cell.h5" --direction $d --set lbm.output_dir="\"$work/split\"" \
    --set lbm.convergence.tolerance=1e-4 > "$work/split$d.log" 2>&1 || { cat "$work/split$d.log"; fail "direction $d failed"; }
done
"$lbm" collect --input "$work/cell.h5" --set lbm.output_dir="\"$work/split\"" > "$work/collect.log" 2>&1 \
  || { cat "$work/collect.log"; fail "collect failed"; }
/usr/bin/python3 - "$result" "$work/split/permeability_cell.h5" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    assert np.array_equal(a["permeability/K"][...], b["permeability/K"][...]), (a["permeability/K"][...], b["permeability/K"][...])
PY
# Direction files of another precision or tolerance are refused by name (they were assembled).
"$lbm" --input "$work/cell.h5" --direction 1 --set lbm.output_dir="\"$work/split\"" \
  --set lbm.convergence.tolerance=1e-3 --set lbm.precision=float > "$work/split1b.log" 2>&1 ||
  { cat "$work/split1b.log"; fail "direction 1 in float failed"; }
set +e
"$lbm" collect --input "$work/cell.h5" --set lbm.output_dir="\"$work/split\"" > "$work/collect3.log" 2>&1
code=$?
set -e
[ "$code" -eq 3 ] && grep -q "direction1.h5: precision, convergence tolerance differ(s) from direction 0's" \
  "$work/collect3.log" || { cat "$work/collect3.log"; fail "collect of mixed precision exited $code, expected 3 naming both"; }
rm "$work/split/permeability_cell_direction1.h5"
set +e
"$lbm" collect --input "$work/cell.h5" --set lbm.output_dir="\"$work/split\"" > "$work/collect2.log" 2>&1
code=$?
set -e
[ "$code" -eq 3 ] && grep -q "direction1" "$work/collect2.log" || { cat "$work/collect2.log"; fail "collect without a direction file exited $code, expected 3 naming it"; }

set +e
"$lbm" --input "$work/cell.h5" --set lbm.output_dir="\"$work\"" --set lbm.tau=0.5005 --set lbm.body_force=0.05 \
  > "$work/diverge.log" 2>&1
code=$?
set -e
[ "$code" -eq 4 ] || { cat "$work/diverge.log"; fail "diverging run exited $code, expected 4"; }
grep -qE "Mach|non-finite" "$work/diverge.log" || fail "divergence message does not name the cause"
[ "$(md5sum < "$result")" = "$checksum" ] || fail "a diverged run changed the earlier result"
ls "$work" | grep -q '\.tmp-' && fail "a temporary file was left behind"

set +e
"$lbm" --input "$work/cell.h5" --set lbm.output_dir="\"$work/limit\"" --set lbm.max_steps=200 > "$work/limit.log" 2>&1
code=$?
set -e
[ "$code" -eq 5 ] || { cat "$work/limit.log"; fail "step-limited run exited $code, expected 5"; }
grep -q "not converged after 200 steps" "$work/limit.log" || fail "the step limit is not reported as 200 steps"
[ ! -e "$work/limit/permeability_cell.h5" ] || fail "a non-converged run wrote a result"

# A limit below two convergence checks could never converge (it once ran 100 steps for 50 asked).
set +e
"$lbm" --input "$work/cell.h5" --set lbm.output_dir="\"$work/limit\"" --set lbm.max_steps=50 > "$work/short.log" 2>&1
code=$?
set -e
[ "$code" -eq 2 ] || { cat "$work/short.log"; fail "a 50-step limit exited $code, expected 2"; }
grep -q "lbm.max_steps = 50 is below two convergence checks" "$work/short.log" ||
  { cat "$work/short.log"; fail "a 50-step limit is not explained"; }
# A pore space that does not connect across the cell along x1 (a solid plane) carries no flow
# along it: K11 = 0 and the x1 row and column are zero, with a warning naming x1 (it gave K11 =
# -1.8e-13 m^2 with exit 0, later a refusal of the whole tensor).
/usr/bin/python3 - "$work/cell.h5" "$work/walled.h5" "$work/slit.h5" <<'PY'
import shutil, sys, h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    phase = f["image/phase"]
    solid = phase[...]
    solid[:, :, 5] = 1  # dims [n3, n2, n1]: the plane x1 = 5
    phase[...] = solid
# A slit 3 voxels wide between solid planes normal to x3: a narrow throat along x1 and x2.
shutil.copy(sys.argv[1], sys.argv[3])
with h5py.File(sys.argv[3], "r+") as f:
    phase = f["image/phase"]
    solid = phase[...]
    solid[...] = 1
    solid[2:5, :, :] = 0
    phase[...] = solid
PY
"$lbm" --input "$work/walled.h5" --set lbm.output_dir="\"$work/walled\"" > "$work/walled.log" 2>&1 ||
  { cat "$work/walled.log"; fail "a walled image failed"; }
grep -q "pore space does not connect across the cell along x1.*K11 = 0" "$work/walled.log" ||
  { cat "$work/walled.log"; fail "a walled image gave no warning naming x1"; }
/usr/bin/python3 - "$work/walled/permeability_walled.h5" <<'PY' || fail "a walled image's K is wrong"
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as f:
    g = f["permeability"]
    k, runs = g["K_lattice"][...], g["runs"]
    assert (k[0, :] == 0).all() and (k[:, 0] == 0).all(), k
    assert k[1, 1] > 0 and k[2, 2] > 0, k
    assert list(runs["percolates"][...]) == [0, 1, 1], runs["percolates"][...]
    assert runs["throat_width"][0] == 0 and (runs["throat_width"][1:] > 0).all(), runs["throat_width"][...]
    print(f"walled image: K_lattice diagonal {np.diag(k)}, throat widths {runs['throat_width'][...]}")
PY
"$lbm" --input "$work/slit.h5" --set lbm.output_dir="\"$work/slit\"" --set lbm.convergence.tolerance=1e-4 \
  > "$work/slit.log" 2>&1 || { cat "$work/slit.log"; fail "a slit image failed"; }
grep -q "the narrowest throat along x1 is 3.0 voxels wide" "$work/slit.log" &&
  grep -q "the narrowest throat along x2 is 3.0 voxels wide" "$work/slit.log" &&
  grep -q "does not connect across the cell along x3" "$work/slit.log" ||
  { cat "$work/slit.log"; fail "a 3-voxel slit gave no throat warnings"; }
echo "cli_run.sh: all checks passed"
