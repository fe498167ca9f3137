#!/usr/bin/python3
"""The diagonal permeabilities of several aniso-lbm results of one checkpoint side by side, to check
how a result depends on the method or the resolution (docs/paper-comparison.md, section 5).

Each input is a whole result (permeability_<stem>.h5, /permeability/K) or one direction
(permeability_<stem>_directionD.h5 of `aniso-lbm --direction D`). From a direction file the
diagonal entry comes from the run along its axis with periodic or no-slip side faces,
k_DD = nu <j_D> / F (the paper's k_ii; free-slip runs only feed the off-diagonal terms).
Directions of one label are merged, so a label may name one file per axis.

usage: permeability_checks_csv.py OUTPUT.csv LABEL=FILE [LABEL=FILE ...]
  writes one row per label: voxels per d50, method, K11, K22, K33 [m^2] (empty where not run),
  K11/K33, and (K11 - K33)/tr K and (K22 - K33)/tr K where all three are known
"""
import csv
import sys

import runner  # noqa: F401 (puts the plotting library's readers on the path)
from readers import read_permeability

WALLS_PERIODIC, WALLS_NO_SLIP = 0, 1


def diagonal_of(path):
    """{axis (0-2): k_axis in m^2}, the method, and the voxel size."""
    flow = read_permeability(path)
    method, voxel = flow["method"], float(flow["voxel_size"])
    if "K" in flow:
        return {a: float(flow["K"][a, a]) for a in range(3)}, method, voxel
    axis = int(flow["axis"])
    nu = (float(flow["tau"]) - 0.5) / 3.0
    runs = flow["runs"]
    for r, walls in enumerate(runs["walls"]):
        if walls in (WALLS_PERIODIC, WALLS_NO_SLIP):
            j = float(runs["mean_momentum"][r, axis])
            return {axis: nu * j / float(flow["body_force"]) * voxel**2}, method, voxel
    sys.exit(f"permeability_checks_csv.py: {path} has no periodic or no-slip run")


def main():
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    rows = {}
    for argument in sys.argv[2:]:
        label, path = argument.rsplit("=", 1)
        diagonal, method, voxel = diagonal_of(path)
        row = rows.setdefault(label, {"label": label, "method": method, "voxel_size_m": voxel, "K": {}})
        if row["method"] != method or row["voxel_size_m"] != voxel:
            sys.exit(f"permeability_checks_csv.py: {path} differs from the other files of {label!r}")
        row["K"].update(diagonal)
    with open(sys.argv[1], "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["label", "method", "voxel_size_m", "K_11", "K_22", "K_33", "K11_over_K33",
                         "K11_minus_K33_over_trace", "K22_minus_K33_over_trace"])
        for row in rows.values():
            K = row["K"]
            cells = [f"{K[a]:.9g}" if a in K else "" for a in range(3)]
            ratio = f"{K[0] / K[2]:.6g}" if 0 in K and 2 in K else ""
            if len(K) == 3:
                trace = sum(K.values())
                anisotropy = [f"{(K[0] - K[2]) / trace:.6g}", f"{(K[1] - K[2]) / trace:.6g}"]
            else:
                anisotropy = ["", ""]
            writer.writerow([row["label"], row["method"], f"{row['voxel_size_m']:.6g}", *cells, ratio, *anisotropy])
            print(row["label"], row["method"], cells, ratio, anisotropy)


if __name__ == "__main__":
    main()
