#!/bin/bash
# aniso-lbm against Palabos on the same voxel image: the diagonal permeability K_ii along the axes
# given, each code with the same tau, body force and convergence tolerance (aniso-lbm: D3Q19 TRT,
# magic 3/16; Palabos 1.5: D3Q19 BGK with Guo's forcing, palabos_permeability.cpp beside this
# script; both halfway bounce-back, every face periodic). Prints K_lattice per axis and code and the
# ratios between the axes, the quantity whose sign docs/paper-comparison.md compares with the paper.
# Results: docs/validation.md, "LBM permeability", "Against Palabos on a packing image".
#
# usage: permeability_against_palabos.sh IMAGE.h5 [AXES="0 2"] [TAU=0.8] [WORK=/tmp/aniso-lbm-palabos]
# environment: ANISO_BUILD (default /work/build), TOLERANCE (default 1e-5), MAX_STEPS (default 400000)
set -euo pipefail
image=${1:?usage: permeability_against_palabos.sh IMAGE.h5 [AXES] [TAU] [WORK]}
axes=${2:-"0 2"}
tau=${3:-0.8}
work=${4:-/tmp/aniso-lbm-palabos}
build=${ANISO_BUILD:-/work/build}
tolerance=${TOLERANCE:-1e-5}
max_steps=${MAX_STEPS:-400000}
here=$(cd "$(dirname "$0")" && pwd)
peer=$here/../../perf/lbm_peer
[ -f "$image" ] || { echo "permeability_against_palabos.sh: no image $image" >&2; exit 2; }
[ -x "$build/lbm/aniso-lbm" ] || { echo "permeability_against_palabos.sh: $build/lbm/aniso-lbm is missing" >&2; exit 2; }
mkdir -p "$work"
[ -x "$work/palabos_permeability" ] || "$peer/build.sh" "$work" "$here/palabos_permeability.cpp" > /dev/null
read -r n1 n2 n3 < <(/usr/bin/python3 "$peer/image_to_palabos.py" "$image" "$work/geometry.txt")
echo "image $image: ${n1}x${n2}x${n3}; tau $tau; $(date -u +%FT%TZ); load average $(cut -d' ' -f1-3 /proc/loadavg)"
: >"$work/results.txt"
for axis in $axes; do
  rm -rf "$work/aniso_$axis"
  "$build/lbm/aniso-lbm" --input "$image" --direction "$axis" --set "lbm.output_dir=\"$work/aniso_$axis\"" \
    --set lbm.tau="$tau" --set lbm.convergence.criterion='"change"' --set lbm.convergence.tolerance="$tolerance" --set lbm.max_steps="$max_steps" \
    > "$work/aniso_$axis.log" 2>&1 || { echo "aniso-lbm failed: $work/aniso_$axis.log" >&2; exit 1; }
  # aniso's K_ii = nu <j_i> / F from its direction file, and its force for Palabos
  read -r k_aniso force steps < <(/usr/bin/python3 - "$work/aniso_$axis" "$axis" <<'PY'
import glob, sys
import h5py
with h5py.File(glob.glob(f"{sys.argv[1]}/*_direction{sys.argv[2]}.h5")[0], "r") as f:
    g = f["direction"]
    runs = g["runs"]
    nu = (float(g.attrs["tau"]) - 0.5) / 3
    force = float(g.attrs["body_force"])
    j = float(runs["mean_momentum"][()].reshape(-1, 3)[0, int(sys.argv[2])])
    print(f"{nu * j / force:.10g} {force:.10g} {int(runs['steps'][()].sum())}")
PY
)
  "$work/palabos_permeability" "$work/geometry.txt" "$n1" "$n2" "$n3" "$axis" "$tau" "$force" "$max_steps" \
    "$tolerance" > "$work/palabos_$axis.log" 2>&1 || { echo "Palabos did not converge: $work/palabos_$axis.log" >&2; exit 1; }
  k_palabos=$(sed -n 's/.*K_lattice \([0-9.eE+-]*\) converged.*/\1/p' "$work/palabos_$axis.log")
  palabos_steps=$(sed -n 's/^axis [0-9] steps \([0-9]*\) .*/\1/p' "$work/palabos_$axis.log")
  echo "$axis $k_aniso $steps $k_palabos $palabos_steps" >> "$work/results.txt"
done
/usr/bin/python3 - "$work/results.txt" <<'PY'
import sys
rows = [line.split() for line in open(sys.argv[1])]
print("| axis | aniso K_lattice (steps) | Palabos K_lattice (steps) | Palabos / aniso |")
print("| --- | --- | --- | --- |")
for axis, ka, sa, kp, sp in rows:
    print(f"| x{int(axis) + 1} | {float(ka):.5g} ({sa}) | {float(kp):.5g} ({sp}) | {float(kp) / float(ka):.4f} |")
for i in range(len(rows)):
    for j in range(i + 1, len(rows)):
        a, b = rows[i], rows[j]
        print(f"K{int(a[0]) + 1}{int(a[0]) + 1} / K{int(b[0]) + 1}{int(b[0]) + 1}: aniso {float(a[1]) / float(b[1]):.4f}, "
              f"Palabos {float(a[3]) / float(b[3]):.4f}")
PY
