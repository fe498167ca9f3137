#!/usr/bin/python3
"""Convert an aniso DEM checkpoint (docs/formats/checkpoint.md) to a
LAMMPS/LIGGGHTS `atom_style granular` (LAMMPS: `sphere`) data file.

usage: checkpoint_to_data.py CHECKPOINT.h5 OUT.data [--info OUT.txt]

Writes the periodic box [0, L_a) of /cell/lengths, one atom type, the
Atoms section (id type diameter density x y z, ids from 1) and the
Velocities section (id vx vy vz wx wy wz: the fluctuating velocities of the
checkpoint; the affine part of the deforming cell is not carried over, the
peer's box is static). The per-particle density is mass / (pi/6 d^3).

--info writes `key value` lines the benchmark script reads: particles,
contacts (rows of /contacts with overlap > 0), time_step, cell lengths,
material parameters, skin, d50.
"""
import argparse
import math
import sys

import h5py
import numpy as np


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkpoint")
    parser.add_argument("data")
    parser.add_argument("--info")
    args = parser.parse_args()

    with h5py.File(args.checkpoint, "r") as f:
        if f.attrs["schema"] != "aniso-checkpoint" or int(f.attrs["schema_version"]) != 1:
            print(f"{args.checkpoint}: not an aniso-checkpoint version 1", file=sys.stderr)
            return 2
        aspect = f["particles/aspect_ratio"][:]
        if np.any(aspect != 1.0):
            print(f"{args.checkpoint}: non-spherical particles cannot be converted", file=sys.stderr)
            return 2
        lengths = f["cell/lengths"][:]
        x = f["particles/position"][:]
        d = f["particles/diameter"][:]
        m = f["particles/mass"][:]
        v = f["particles/velocity"][:]
        w = f["particles/angular_velocity"][:]
        overlap = f["contacts/overlap"][:]
        dt = float(f.attrs["time_step"])
        params = {k: float(val) for k, val in f["parameters"].attrs.items()
                  if not k.endswith("_units") and k != "description"}

    n = len(d)
    rho = m / (math.pi / 6.0 * d**3)
    # Positions must lie in [0, L): wrap defensively (the checkpoint promises it).
    x = np.mod(x, lengths)
    x = np.where(x >= lengths, 0.0, x)

    with open(args.data, "w") as out:
        out.write(f"aniso checkpoint {args.checkpoint} converted by checkpoint_to_data.py\n\n")
        out.write(f"{n} atoms\n1 atom types\n\n")
        for axis, name in enumerate("xyz"):
            out.write(f"0 {lengths[axis]:.17g} {name}lo {name}hi\n")
        out.write("\nAtoms\n\n")
        for i in range(n):
            out.write(f"{i + 1} 1 {d[i]:.17g} {rho[i]:.17g} {x[i, 0]:.17g} {x[i, 1]:.17g} {x[i, 2]:.17g}\n")
        out.write("\nVelocities\n\n")
        for i in range(n):
            out.write(f"{i + 1} {v[i, 0]:.17g} {v[i, 1]:.17g} {v[i, 2]:.17g} "
                      f"{w[i, 0]:.17g} {w[i, 1]:.17g} {w[i, 2]:.17g}\n")

    if args.info:
        with open(args.info, "w") as out:
            out.write(f"particles {n}\n")
            out.write(f"contacts {int(np.count_nonzero(overlap > 0))}\n")
            out.write(f"time_step {dt:.17g}\n")
            out.write(f"cell {lengths[0]:.17g} {lengths[1]:.17g} {lengths[2]:.17g}\n")
            out.write(f"d_min {d.min():.17g}\nd_max {d.max():.17g}\n")
            out.write(f"density_mean {rho.mean():.17g}\n")
            for key in ("shear_modulus", "poisson_ratio", "friction", "damping_ratio", "d50", "skin"):
                if key in params:
                    out.write(f"{key} {params[key]:.17g}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
