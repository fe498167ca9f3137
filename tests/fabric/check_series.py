#!/usr/bin/python3
"""Recomputes every correlation of `aniso-fabric series` with numpy.corrcoef from the series CSV
and the linked probe / permeability / void files, and compares (|difference| <= 1e-12).

usage: check_series.py INPUT_FOLDER RESULT_FOLDER"""
import csv
import glob
import math
import os
import sys

import h5py
import numpy as np


def read_series(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def column(rows, name):
    return np.array([float(r[name]) for r in rows])


def diff(rows, name, axis):
    return column(rows, f"{name}_{axis}{axis}") - column(rows, f"{name}_33")


def corr(x, y):
    return float(np.corrcoef(x, y)[0, 1])


def normalized(diagonal, axis):
    return (diagonal[axis - 1] - diagonal[2]) / (sum(diagonal) / 3.0)


def main(inputs, results):
    rows = read_series(os.path.join(results, "fabric_series.csv"))
    with open(os.path.join(results, "fabric_series_correlations.csv"), newline="") as f:
        reported = list(csv.DictReader(f))
    row_of = {r["source"]: k for k, r in enumerate(rows)}
    probes = {}
    for path in sorted(glob.glob(os.path.join(inputs, "probe_*.h5"))):
        with h5py.File(path) as f:
            probes[row_of[f["stiffness"].attrs["source"]]] = f["stiffness/C"][()]
    voids, perm = {}, {}
    for path in sorted(glob.glob(os.path.join(inputs, "voids_*.h5"))):
        with h5py.File(path) as f:
            voids[row_of[f["voids"].attrs["source"]]] = (f["voids/free_path_median"][()], f["voids/breadth_median"][()])
    for path in sorted(glob.glob(os.path.join(inputs, "permeability_*.h5"))):
        with h5py.File(path) as f:
            source = f["permeability"].attrs["source"]
            K = f["permeability/K"][()]
        if source in row_of:  # the checkpoint itself, as aniso-lbm records it
            perm[row_of[source]] = K
            continue
        with h5py.File(os.path.join(inputs, source)) as g:  # a voxel image
            perm[row_of[g["image/phase"].attrs["source"]]] = K
    checked = 0
    for r in reported:
        measure, against = r["measure"], r["against"]
        expected = []
        for axis in (1, 2):
            if against == "stress":
                x = diff(rows, measure, axis)
                y = -diff(rows, "stress", axis)
            elif measure == "C":
                at = sorted(probes)
                x = np.array([probes[k][axis - 1, axis - 1] - probes[k][2, 2] for k in at])
                y = np.array([diff(rows, against, axis)[k] for k in at])
            else:
                at = sorted(set(perm) & set(voids))
                which = 0 if against == "L" else 1
                x = np.array([normalized(np.diag(perm[k]), axis) for k in at])
                y = np.array([normalized(voids[k][which], axis) for k in at])
            with np.errstate(invalid="ignore", divide="ignore"):
                expected.append(corr(x, y) if np.std(x) > 0 and np.std(y) > 0 else math.nan)
        for value, want, label in ((float(r["c1"]), expected[0], "c1"), (float(r["c2"]), expected[1], "c2")):
            if math.isnan(want) and math.isnan(value):
                continue
            if not abs(value - want) <= 1e-12:
                sys.exit(f"{measure} vs {against} {label}: aniso {value!r}, numpy {want!r}")
            checked += 1
    kinds = {(r["measure"], r["against"]) for r in reported}
    for needed in (("H_strong", "stress"), ("C", "H"), ("K", "L"), ("K", "R")):
        if needed not in kinds:
            sys.exit(f"correlation {needed} missing from the report")
    if checked < 30:
        sys.exit(f"only {checked} finite correlations checked")
    print(f"{checked} correlations equal numpy's")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
