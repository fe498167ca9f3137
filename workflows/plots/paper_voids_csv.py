#!/usr/bin/python3
"""The CSVs of a campaign run's void and permeability stages (the paper figures' input).

Reads RUN_FOLDER/voxel/voids_load_NNN.h5 (aniso-voxel), RUN_FOLDER/lbm/permeability_image_load_NNN.h5
(aniso-lbm, where run) and the checkpoints RUN_FOLDER/dem/load_NNN.h5 they came from (for the strain),
the campaign's run folder (docs/user-guide.md, "The run folder"), and writes into OUTPUT_FOLDER:

  voids.csv        one row per checkpoint: strain, porosity, the median void size (ball, eq. (fr)), the
                   median free paths l_i (spar, eq. (fli)) and radial breadths r_i (disk, eq. (fri)) in
                   units of d50, and the diagonals of L^v (eq. (Lambdaii)) and R^v (eq. (Rii))
  void_curves.csv  the distributions f_rho, f_l_i, f_r_i at the first and last checkpoint (paper Fig.
                   VoidDistrib: 0% and 60%), sizes in units of d50
  permeability.csv one row per checkpoint with an LBM result: strain, the tensor K [m^2], its
                   anisotropies (K11 - K33)/tr K and (K22 - K33)/tr K (paper Fig. K_vs_strain), and per
                   direction the steps, the Reynolds number and the narrowest throat [voxel]

usage: paper_voids_csv.py RUN_FOLDER OUTPUT_FOLDER
"""
import csv
import glob
import os
import re
import sys

import h5py
import numpy as np

AXES = (1, 2, 3)
CURVES = ["ball"] + [f"{kind}_x{a}" for kind in ("spar", "disk") for a in AXES]


def checkpoint_strain(run, stem):
    """Engineering strain eps_11 of the checkpoint (cell length over its reference length, minus 1)."""
    path = os.path.join(run, "dem", f"{stem}.h5")
    if not os.path.exists(path):
        sys.exit(f"paper_voids_csv.py: {path} is missing: the strain of {stem} comes from its checkpoint")
    with h5py.File(path, "r") as f:
        return float(f["cell/lengths"][0] / f["cell/reference_lengths"][0] - 1.0)


def stem_of(path, prefix):
    return os.path.basename(path)[len(prefix):-len(".h5")]


def void_rows(run):
    rows, curves = [], {}
    for path in sorted(glob.glob(os.path.join(run, "voxel", "voids_load_*.h5"))):
        stem = stem_of(path, "voids_")
        with h5py.File(path, "r") as f:
            g = f["voids"]
            d50 = float(g.attrs["d50"])
            row = {"checkpoint": stem, "strain_11": checkpoint_strain(run, stem),
                   "porosity": float(g["porosity"][()]),
                   "void_size_median_d50": float(g["void_size_median"][()]) / d50}
            for a in AXES:
                row[f"free_path_median_{a}_d50"] = float(g["free_path_median"][a - 1]) / d50
            for a in AXES:
                row[f"breadth_median_{a}_d50"] = float(g["breadth_median"][a - 1]) / d50
            for a in AXES:
                row[f"L_v_{a}{a}"] = float(g["L_v"][a - 1])
            for a in AXES:
                row[f"R_v_{a}{a}"] = float(g["R_v"][a - 1])
            curves[stem] = {name: (g[name]["length_d50" if name.startswith("spar") else "radius_d50"][()],
                                   g[name]["fraction"][()]) for name in CURVES}
        rows.append(row)
    return rows, curves


def permeability_rows(run, strains):
    rows = []
    # Only the collected results: the per-direction files of a job array lie beside them.
    for path in sorted(glob.glob(os.path.join(run, "lbm", "permeability_image_load_*.h5"))):
        stem = stem_of(path, "permeability_image_")
        if not re.fullmatch(r"load_\d+", stem):
            continue
        with h5py.File(path, "r") as f:
            g = f["permeability"]
            K = g["K"][()]
            runs = g["runs"]
            row = {"checkpoint": stem, "strain_11": strains.get(stem, checkpoint_strain(run, stem)),
                   "porosity": float(g.attrs["porosity"]), "tau": float(g.attrs["tau"])}
            for i in AXES:
                for j in AXES:
                    row[f"K_{i}{j}"] = float(K[i - 1, j - 1])
            trace = float(np.trace(K))
            row["K11_minus_K33_over_trace"] = (K[0, 0] - K[2, 2]) / trace
            row["K22_minus_K33_over_trace"] = (K[1, 1] - K[2, 2]) / trace
            row["symmetry_error"] = float(g.attrs["symmetry_error"])
            for r, axis in enumerate(runs["axis"][()]):
                row[f"steps_{axis}"] = int(runs["steps"][r])
                row[f"reynolds_{axis}"] = float(runs["reynolds"][r])
                row[f"throat_width_{axis}_voxels"] = float(runs["throat_width"][r])
        rows.append(row)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.9g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"wrote {path} ({len(rows)} rows)")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run, out = sys.argv[1:]
    rows, curves = void_rows(run)
    if not rows:
        sys.exit(f"paper_voids_csv.py: no {run}/voxel/voids_load_*.h5: run the campaign's voxel stage first")
    os.makedirs(out, exist_ok=True)
    write_csv(os.path.join(out, "voids.csv"), rows)
    strains = {r["checkpoint"]: r["strain_11"] for r in rows}
    curve_rows = []
    for stem in (rows[0]["checkpoint"], rows[-1]["checkpoint"]):
        for name in CURVES:
            sizes, fractions = curves[stem][name]
            curve_rows += [{"checkpoint": stem, "strain_11": strains[stem], "distribution": name,
                            "size_d50": float(s), "fraction": float(v)} for s, v in zip(sizes, fractions)]
    write_csv(os.path.join(out, "void_curves.csv"), curve_rows)
    flow = permeability_rows(run, strains)
    if flow:
        write_csv(os.path.join(out, "permeability.csv"), flow)


if __name__ == "__main__":
    main()
