#!/usr/bin/env python3
"""Checks of tests/dem/replicate.sh, run in one shape's folder: prepared.h5 and its copies
x222.h5 (2 x 2 x 2), x123.h5 (1 x 2 x 3) and x111.h5, with fabric.h5 of the first three, a
200-step hold of each (hold_<name>.csv), a 0.1% load (load_<name>/history.csv) and a relax
(relaxed_<name>.h5) of prepared.h5 and x222.h5.

usage: replicate_checks.py SHAPE   (spheres or ovoids: the hold's tolerance)
"""
import sys

import h5py
import numpy as np

SHAPE = sys.argv[1]
# After the first force passes the copies' p follows the original's to round-off: their
# positions carry the rounding of x + i L, and an ovoid's contact the Newton tolerance of its
# narrow phase (measured over 200 steps: 6e-13 for spheres, 3e-11 for ovoids).
HOLD_TOLERANCE = {"spheres": 1e-11, "ovoids": 1e-9}[SHAPE]
# A 0.1% loading amplifies that round-off (measured: 5e-10 for spheres, 3e-11 for ovoids).
LOAD_TOLERANCE = 1e-7
results = {}


def check(name, ok):
    results[f"{SHAPE}: {name}"] = bool(ok)


def relative(a, b):
    """Largest |a - b| over the largest |a| (0 for two zero arrays)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    scale = np.abs(a).max()
    return np.abs(a - b).max() / scale if scale > 0 else np.abs(b).max()


def contact_stress(f):
    """(1/V) sum f_i (x) l over the contacts, tension positive, from the stored forces and the
    branch vectors that the positions and image shifts give (independent of aniso's code)."""
    x, lengths = f["particles/position"][:], f["cell/lengths"][:]
    pairs = f["contacts/particles"][:].astype(np.int64)
    branch = x[pairs[:, 1]] + f["contacts/image_shift"][:] * lengths - x[pairs[:, 0]]
    return np.einsum("ca,cb->ab", f["contacts/force"][:], branch) / np.prod(lengths)


def pressure(stress):
    return -np.trace(stress) / 3


def minimum_image(d, lengths):
    return d - lengths * np.round(d / lengths)


def check_tiling(original, tiled, copies, label):
    n, m = len(original["particles/id"]), len(original["contacts/overlap"])
    k = int(np.prod(copies))
    lengths, tiled_lengths = original["cell/lengths"][:], tiled["cell/lengths"][:]
    check(f"{label}: {k} x {n} particles, {k} x {m} contacts",
          len(tiled["particles/id"]) == k * n and len(tiled["contacts/overlap"]) == k * m)
    check(f"{label}: ids 0..N-1", (tiled["particles/id"][:] == np.arange(k * n)).all())
    check(f"{label}: cell and reference lengths times the copies (exact)",
          np.array_equal(tiled_lengths, np.array(copies) * lengths)
          and np.array_equal(tiled["cell/reference_lengths"][:],
                             np.array(copies) * original["cell/reference_lengths"][:]))
    same = [f"cell/{d}" for d in ("strain_rate", "mode", "target", "servo_state", "hold_mean_stress",
                                  "mean_stress_target")] + ["rng/state"]
    check(f"{label}: controller and random streams kept (exact)",
          all(np.array_equal(original[d][()], tiled[d][()]) for d in same))
    check(f"{label}: parameters, time, step and time step kept (exact)",
          dict(original["parameters"].attrs) == dict(tiled["parameters"].attrs)
          and all(original.attrs[a] == tiled.attrs[a] for a in ("time", "step", "time_step")))
    check(f"{label}: provenance attributes replicated_from, replicate_copies",
          tiled.attrs["replicated_from"] == "prepared.h5"
          and tiled.attrs["replicate_copies"] == ",".join(map(str, copies))
          and len(tiled.attrs["replicated_from_hash"]) == 16)
    # Particles: copy c = (i, j, k) holds rows c N .. c N + N - 1, moved by (i Lx, j Ly, k Lz).
    c = np.arange(k * n) // n
    cell = np.stack([c % copies[0], c // copies[0] % copies[1], c // (copies[0] * copies[1])], axis=1)
    moved = minimum_image(tiled["particles/position"][:] - np.tile(original["particles/position"][:], (k, 1))
                          - cell * lengths, tiled_lengths)
    check(f"{label}: each copy's positions moved by whole cell lengths (1e-14 of the cell; "
          f"{np.abs(moved).max() / tiled_lengths.max():.1e})",
          np.abs(moved).max() <= 1e-14 * tiled_lengths.max())
    carried = ("diameter", "aspect_ratio", "mass", "inertia", "orientation", "velocity", "angular_velocity",
               "force", "torque")
    check(f"{label}: every other per-particle dataset repeated (exact)",
          all(np.array_equal(np.tile(original[f"particles/{d}"][:], (k,) + (1,) * (original[f"particles/{d}"].ndim - 1)),
                             tiled[f"particles/{d}"][:]) for d in carried))
    # Contacts: each tiled pair is an original pair's copy, from the lower id, the signs of its
    # vectors turned where the copies reverse it, at the same branch vector.
    pairs = tiled["contacts/particles"][:].astype(np.int64)
    check(f"{label}: contacts in strictly increasing (id_i, id_j) order, id_i < id_j",
          (pairs[:, 0] < pairs[:, 1]).all() and (np.diff(pairs[:, 0] * k * n + pairs[:, 1]) > 0).all())
    a, b = pairs[:, 0] % n, pairs[:, 1] % n
    keys = np.minimum(a, b) * n + np.maximum(a, b)
    original_pairs = original["contacts/particles"][:].astype(np.int64)
    original_keys = original_pairs[:, 0] * n + original_pairs[:, 1]
    row = np.searchsorted(original_keys, keys).clip(0, m - 1)
    check(f"{label}: every contact is a copy of an original one, each original {k} times",
          (original_keys[row] == keys).all() and (np.bincount(row, minlength=m) == k).all())
    sign = np.where(a < b, 1.0, -1.0)[:, None]

    def branches(f):
        x, ij = f["particles/position"][:], f["contacts/particles"][:].astype(np.int64)
        return x[ij[:, 1]] + f["contacts/image_shift"][:] * f["cell/lengths"][:] - x[ij[:, 0]]

    offset = np.abs(branches(tiled) - sign * branches(original)[row]).max()
    check(f"{label}: each contact joins the copy its branch vector reaches (branch vectors equal to "
          f"1e-14 of the cell; {offset / tiled_lengths.max():.1e})", offset <= 1e-14 * tiled_lengths.max())
    check(f"{label}: normal, force and tangential force carried, turned where reversed (exact)",
          all(np.array_equal(tiled[f"contacts/{d}"][:], sign * original[f"contacts/{d}"][:][row])
              for d in ("normal", "force", "tangential_force")))
    check(f"{label}: overlap and sliding carried (exact)",
          all(np.array_equal(tiled[f"contacts/{d}"][:], original[f"contacts/{d}"][:][row])
              for d in ("overlap", "sliding")))
    x, x0 = tiled["particles/position"][:], original["particles/position"][:]
    arm = minimum_image(tiled["contacts/point"][:] - x[pairs[:, 0]], tiled_lengths)
    arm0 = minimum_image(original["contacts/point"][:][row] - x0[a], lengths)
    point_inside = ((tiled["contacts/point"][:] >= 0) & (tiled["contacts/point"][:] < tiled_lengths)).all()
    check(f"{label}: contact points at the contact in the tiled cell (1e-14 of the cell) and inside it",
          np.abs(arm - arm0).max() <= 1e-14 * tiled_lengths.max() and point_inside)
    stress, tiled_stress = contact_stress(original), contact_stress(tiled)
    difference = relative(stress, tiled_stress)
    check(f"{label}: contact stress of the stored forces equal (relative to its largest entry "
          f"{difference:.1e} <= 1e-12)", difference <= 1e-12)
    return pressure(stress)


def walk(f):
    """Every dataset's bytes and every object's attributes, /provenance left out."""
    content = {"/": {k: v for k, v in f.attrs.items()}}

    def visit(name, item):
        if name.startswith("provenance"):
            return
        content[name] = {k: v for k, v in item.attrs.items()}
        if isinstance(item, h5py.Dataset):
            content[name]["<data>"] = (item.dtype.str, item.shape, item[()].tobytes())

    f.visititems(visit)
    return content


with h5py.File("prepared.h5", "r") as original:
    for copies in ((2, 2, 2), (1, 2, 3)):
        label = "x" + "".join(map(str, copies))
        with h5py.File(f"{label}.h5", "r") as tiled:
            p = check_tiling(original, tiled, copies, label)
    with h5py.File("x111.h5", "r") as single:
        a, b = walk(original), walk(single)
        for name in ("replicated_from", "replicated_from_hash", "replicate_copies"):
            b["/"].pop(name)
        def same(x, y):
            return x == y if isinstance(x, tuple) else np.array_equal(x, y)

        differing = sorted(k for k in set(a) | set(b) if k not in a or k not in b
                           or a[k].keys() != b[k].keys() or not all(same(a[k][x], b[k][x]) for x in a[k]))
        check(f"1 x 1 x 1: every dataset and attribute as in the input, /provenance aside "
              f"(differing: {differing})", not differing)

with h5py.File("fabric.h5", "r") as f:
    g = f["checkpoints"]
    check(f"fabric p of the original is the contact stress's ({g['prepared'].attrs['p']:.9g} Pa, 1e-12)",
          abs(g["prepared"].attrs["p"] / p - 1) <= 1e-12)
    intensive = ("mean_normal_force", "p", "q", "void_ratio", "coordination", "coordination_no_rattlers",
                 "chi_torus_per_particle", "strain_11", "strain_22", "strain_33")
    # Contact and particle measures; W320 and W320_normalized are moments about the cell's centre
    # and its box, which the tiling changes.
    tensors = ("stress", "J", "I", "S", "F", "F_strong", "G", "G_strong", "H", "H_strong")
    for name, copies in (("x222", 8), ("x123", 6)):
        o, t = g["prepared"], g[name]
        worst = max(relative(o.attrs[k], t.attrs[k]) for k in intensive)
        check(f"{name}: fabric p, q, void ratio, coordination, mean normal force, strains equal "
              f"(relative {worst:.1e} <= 1e-12)", worst <= 1e-12)
        worst = max(relative(o[k][()], t[k][()]) for k in tensors)
        check(f"{name}: fabric tensors {', '.join(tensors)} equal (relative {worst:.1e} <= 1e-12)",
              worst <= 1e-12)
        counts = ("n_particles", "n_contacts", "n_strong", "n_rattlers", "n_triples", "n_quadruples", "chi_torus")
        check(f"{name}: counts and chi_torus times {copies}, chi_paper - 1 times {copies} (exact)",
              all(t.attrs[k] == copies * o.attrs[k] for k in counts)
              and t.attrs["chi_paper"] - 1 == copies * (o.attrs["chi_paper"] - 1))


def column(path, name):
    return np.genfromtxt(path, delimiter=",", names=True)[name]


p0 = column("hold_prepared.csv", "p")
for name in ("x222", "x123"):
    p1 = column(f"hold_{name}.csv", "p")
    check(f"{name}: hold samples at the original's steps",
          np.array_equal(column("hold_prepared.csv", "step"), column(f"hold_{name}.csv", "step")))
    start, later = abs(p1[0] / p0[0] - 1), np.abs(p1[1:] / p0[1:] - 1).max()
    check(f"{name}: hold starts at the original's p ({start:.1e} <= 1e-13) and its force passes keep it "
          f"over 200 steps ({later:.1e} <= {HOLD_TOLERANCE:g})", start <= 1e-13 and later <= HOLD_TOLERANCE)
history, copies = "load_prepared/history.csv", "load_x222/history.csv"
check("x222: the load writes its history at the original's steps",
      np.array_equal(column(history, "step"), column(copies, "step")))
worst = max(relative(column(history, k), column(copies, k)) for k in ("p", "q", "void_ratio"))
check(f"x222: the load follows the original's p, q, void ratio over 0.1% ({worst:.1e} <= {LOAD_TOLERANCE:g})",
      worst <= LOAD_TOLERANCE)
with h5py.File("relaxed_prepared.h5", "r") as a, h5py.File("relaxed_x222.h5", "r") as b:
    relaxed = abs(pressure(contact_stress(b)) / pressure(contact_stress(a)) - 1)
    check(f"x222: relax ends at the original's step and p ({relaxed:.1e} <= {HOLD_TOLERANCE:g})",
          a.attrs["step"] == b.attrs["step"] and relaxed <= HOLD_TOLERANCE)

for name, ok in results.items():
    print(("ok: " if ok else "FAIL: ") + name)
sys.exit(0 if all(results.values()) else 1)
