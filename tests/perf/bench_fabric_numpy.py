#!/usr/bin/python3
"""Peer for bench_fabric: the contact and particle measures a user would script with h5py and
numpy (vectorised), timed on the same checkpoint, and checked against aniso-fabric's results.

Computes: contact stress (1/V) sum l (x) f, F^c, G^c, H^c and their strong variants, J^p for
spheres/ovoids (axes from the quaternions), W_3^{2,0} of spheres (eq. (W320)) and Z. Not
included (so the peer does less work than aniso): I^s and S^s of ovoids, rattlers, N_3 and N_4.

usage: bench_fabric_numpy.py CHECKPOINT.h5 [FABRIC_RESULTS.h5] [REPEATS=9]"""
import statistics
import sys
import time

import h5py
import numpy as np


def read(path):
    with h5py.File(path) as f:
        c = {name: f["contacts"][name][()] for name in ("particles", "image_shift", "normal", "point", "force")}
        p = {name: f["particles"][name][()] for name in ("diameter", "aspect_ratio", "position", "orientation")}
        lengths = f["cell/lengths"][()]
        d50 = f["parameters"].attrs["d50"]
    return c, p, lengths, d50


def measures(c, p, lengths, d50):
    i, j = c["particles"][:, 0], c["particles"][:, 1]
    l = p["position"][j] + c["image_shift"] * lengths - p["position"][i]
    n, f = c["normal"], c["force"]
    out = {"stress": np.einsum("ka,kb->ab", l, f) / np.prod(lengths)}
    fn = -np.einsum("ka,ka->k", f, n)
    strong = fn > fn.mean()
    for suffix, mask in (("", slice(None)), ("_strong", strong)):
        out["F" + suffix] = np.einsum("ka,kb->ab", n[mask], n[mask]) / n[mask].shape[0]
        out["G" + suffix] = np.einsum("ka,kb->ab", l[mask], l[mask]) / (l[mask].shape[0] * d50**2)
        out["H" + suffix] = np.einsum("ka,kb->ab", l[mask], n[mask]) / (l[mask].shape[0] * d50)
    w, x, y, z = p["orientation"].T  # body z axis in the world: third column of R
    axis = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=1)
    alpha = p["aspect_ratio"]
    J = (np.eye(3)[None] - (1 - alpha)[:, None, None] * np.einsum("ka,kb->kab", axis, axis))
    out["J"] = np.mean(3 / (2 + alpha)[:, None, None] * J, axis=0)
    if np.all(alpha == 1):
        t = p["position"] - 0.5 * lengths
        xc = c["point"] - 0.5 * lengths
        R2 = (0.5 * p["diameter"]) ** 2
        w3 = 4 * np.pi / 3
        out["W320"] = (np.eye(3) * (4 * np.pi / 9) * R2.sum() + w3 * np.einsum("ka,kb->ab", t, t)
                       - w3 * np.einsum("ka,kb->ab", xc, xc))
    out["coordination"] = 2 * len(i) / len(p["diameter"])
    return out


def main():
    path = sys.argv[1]
    results = sys.argv[2] if len(sys.argv) > 2 and sys.argv[2].endswith(".h5") else None
    repeats = int(sys.argv[-1]) if len(sys.argv) > 2 and sys.argv[-1].isdigit() else 9
    reads, computes = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        data = read(path)
        reads.append(time.perf_counter() - start)
        start = time.perf_counter()
        out = measures(*data)
        computes.append(time.perf_counter() - start)
    print(f"numpy read: median {statistics.median(reads):.4f} s; measures: median {statistics.median(computes):.4f} s "
          f"(min {min(computes):.4f}, max {max(computes):.4f}) over {repeats} runs")
    if results:
        with h5py.File(results) as f:
            group = next(iter(f["checkpoints"].values()))
            worst = 0.0
            for name, value in out.items():
                if name == "coordination":
                    mine = group.attrs["coordination"]
                    worst = max(worst, abs(mine - value) / abs(value))
                    continue
                mine = group[name][()]
                worst = max(worst, np.max(np.abs(mine - value)) / np.max(np.abs(value)))
        print(f"largest relative difference from aniso-fabric over {len(out)} measures: {worst:.2e}")


if __name__ == "__main__":
    main()
