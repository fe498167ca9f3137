#!/usr/bin/python3
"""Checks that run folder B holds every result of run folder A with the same bits.

usage: compare_runs.py RUN_A RUN_B      exit 0 when identical, 1 naming each differing file and object

Results may name files by path (a probe's `source` attribute, the CSV
columns, report.md, XDMF sidecars), so in every string each folder's own path
is replaced by RUN before comparing. Otherwise:
- HDF5 files: the same groups, datasets and attributes; each dataset and each
  attribute with the same type, shape and bytes. /provenance is left out: it
  records the date, the command line and the rank count. So are the few
  objects in NOT_RESULTS, wherever they occur, in HDF5 files and as CSV
  columns: they identify the input or time the run.
- CSV files: cell by cell, without the NOT_RESULTS columns.
- Every other file: byte for byte (PNG figures included).
Job logs (slurm/), the stages' logs (logs/), the load.done stamp and hidden files are not results,
at any depth (make paper's folder holds one run folder per shape and realisation).
"""
import csv
import os
import sys

import h5py
import numpy as np


def normalized(value, root):
    """Strings with the run folder replaced; everything else as it is."""
    if isinstance(value, bytes):
        return value.replace(root.encode(), b"RUN")
    if isinstance(value, str):
        return value.replace(root, "RUN")
    if isinstance(value, np.ndarray) and value.dtype.kind in "OSU":
        return [normalized(v, root) for v in value.ravel().tolist()]
    return value


def same_value(a, b, root_a, root_b):
    a, b = normalized(a, root_a), normalized(b, root_b)
    if isinstance(a, (np.ndarray, np.generic)) or isinstance(b, (np.ndarray, np.generic)):
        a, b = np.asarray(a), np.asarray(b)
        return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
    return type(a) is type(b) and a == b


# name -> why it differs between runs that computed the same results
NOT_RESULTS = {
    "source_hash": "a hash of the input file's bytes, whose /provenance holds a date",
    "image_hash": "a hash of the voxel image file's bytes, whose /provenance holds a date",
    "seconds": "the wall time of a run (aniso-lbm's /permeability/runs/seconds)",
    "run_id": "names one loading run (date and random bits): two runs of one config get two",
    "timing": "where a run's wall time went (history.h5's /timing group)",
}


def h5_differences(path_a, path_b, root_a, root_b):
    differences = []
    with h5py.File(path_a, "r") as a, h5py.File(path_b, "r") as b:
        def compare(name_a, object_a, object_b):
            label = object_a.name
            if sorted(object_a.attrs) != sorted(object_b.attrs):
                differences.append(f"{label}: attributes {sorted(object_a.attrs)} vs {sorted(object_b.attrs)}")
            for key in object_a.attrs:
                if key in object_b.attrs and key not in NOT_RESULTS and not same_value(object_a.attrs[key], object_b.attrs[key], root_a, root_b):
                    differences.append(f"{label}: attribute {key}")
            if isinstance(object_a, h5py.Group):
                members_a = sorted(k for k in object_a if object_a[k].name != "/provenance" and k not in NOT_RESULTS)
                members_b = sorted(k for k in object_b if object_b[k].name != "/provenance" and k not in NOT_RESULTS)
                if members_a != members_b:
                    differences.append(f"{label}: members {members_a} vs {members_b}")
                for key in members_a:
                    if key in object_b:
                        compare(key, object_a[key], object_b[key])
            elif not isinstance(object_b, h5py.Dataset):
                differences.append(f"{label}: a dataset in one file, not in the other")
            elif object_a.dtype != object_b.dtype or object_a.shape != object_b.shape:
                differences.append(f"{label}: {object_a.dtype}{object_a.shape} vs {object_b.dtype}{object_b.shape}")
            elif not same_value(object_a[()], object_b[()], root_a, root_b):
                differences.append(f"{label}: values")

        compare("/", a, b)
    return differences


def csv_rows(path, root):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [k for k, name in enumerate(rows[0] if rows else []) if name not in NOT_RESULTS]
    return [[normalized(row[k], root) if k < len(row) else None for k in keep] for row in rows]


def text_or_bytes_equal(path_a, path_b, root_a, root_b):
    if path_a.endswith(".csv"):
        return csv_rows(path_a, root_a) == csv_rows(path_b, root_b)
    with open(path_a, "rb") as fa, open(path_b, "rb") as fb:
        return normalized(fa.read(), root_a) == normalized(fb.read(), root_b)


def main(root_a, root_b):
    root_a, root_b = os.path.abspath(root_a), os.path.abspath(root_b)
    compared, differing = 0, 0
    for folder, subfolders, files in os.walk(root_a):
        # At any depth: make paper's root holds one run folder per shape and realisation.
        subfolders[:] = sorted(d for d in subfolders if d not in ("slurm", "logs"))
        for name in sorted(files):
            if name.startswith(".") or name == "load.done":
                continue
            relative = os.path.relpath(os.path.join(folder, name), root_a)
            path_a, path_b = os.path.join(root_a, relative), os.path.join(root_b, relative)
            compared += 1
            if not os.path.exists(path_b):
                print(f"compare_runs: {relative} is in {root_a} but not in {root_b}", file=sys.stderr)
                differing += 1
            elif name.endswith(".h5"):
                problems = h5_differences(path_a, path_b, root_a, root_b)
                for problem in problems:
                    print(f"compare_runs: {relative} differs: {problem}", file=sys.stderr)
                differing += bool(problems)
            elif not text_or_bytes_equal(path_a, path_b, root_a, root_b):
                print(f"compare_runs: {relative} differs", file=sys.stderr)
                differing += 1
    if compared == 0:
        sys.exit(f"compare_runs: no results in {root_a}")
    if differing:
        sys.exit(f"compare_runs: {differing} of {compared} files differ between {root_a} and {root_b}")
    print(f"compare_runs: {compared} files identical in {root_a} and {root_b}", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
