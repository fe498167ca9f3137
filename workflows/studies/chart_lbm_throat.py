#!/usr/bin/python3
"""Where the LBM fails: error of K against the narrowest throat in voxels
(docs/charts/lbm_throat_error.png, docs/methods/lbm.md "Where the method fails").

Simple cubic sphere arrays at the solid fractions of Zick & Homsy (1982, Table 2; k/a^2 as in
shared/reference/permeability.md), each at several cell sides, so that the window between the
spheres spans 1 to about 10 voxels: one aniso-lbm run along x1 (periodic body force, tau = 1,
tolerance 1e-6), its K11 against Zick & Homsy's, beside the throat width the run records
(/permeability/runs/throat_width). Rows go to lbm_throat_error.csv; runs already listed there are
reused (delete the csv to redo them).

usage: chart_lbm_throat.py BUILD_FOLDER WORK_FOLDER OUTPUT_FOLDER
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from runner import RunTable, main_guarded, run_cached, settings_arguments, stage  # noqa: E402
from readers import read_permeability  # noqa: E402

# phi -> k / a^2 of Zick & Homsy
ZICK_HOMSY = {0.125: 0.41421, 0.216: 0.13824, 0.343: 0.042070, 0.45: 0.017574, 0.5236: 0.010081}
SIDES = [6, 8, 10, 12, 16, 20, 24, 32, 40]
FIELDS = ["phi", "side", "throat_width", "k11_over_a2", "relative_error", "steps", "seconds"]
THRESHOLD = 0.02


def run(build, work, phi, side):
    image = os.path.join(work, f"sc_{phi}_{side}.h5")
    run_cached([f"{build}/tests/lbm/make_lbm_image", "sphere_array", image, "--side", side, "--solid-fraction", phi,
                "--voxel-size", "1"], work, outputs=[image], log=f"sc_{phi}_{side}.log")
    out = os.path.join(work, f"out_{phi}_{side}")
    stem = os.path.splitext(os.path.basename(image))[0]
    result = os.path.join(out, f"permeability_{stem}_direction0.h5")
    run_cached([stage(build, "lbm"), "--input", image, "--direction", "0",
                *settings_arguments([f'lbm.output_dir="{out}"', "lbm.convergence.criterion=\"change\"", "lbm.convergence.tolerance=1e-6", "lbm.tau=1.0",
                                     "lbm.body_force=1e-6"])], out, outputs=[result])
    runs = read_permeability(result)["runs"]
    momentum = float(runs["mean_momentum"][0, 0])
    throat = float(runs["throat_width"][0])
    steps, seconds = int(runs["steps"][0]), float(runs["seconds"][0])
    nu = (1.0 - 0.5) / 3.0
    radius = side * (3 * phi / (4 * math.pi)) ** (1 / 3)  # the continuous sphere of the cell
    k_over_a2 = nu * momentum / 1e-6 / radius ** 2
    return {"throat_width": throat, "k11_over_a2": k_over_a2,
            "relative_error": k_over_a2 / ZICK_HOMSY[phi] - 1, "steps": steps, "seconds": seconds}


def main():
    build, work, output = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    os.makedirs(output, exist_ok=True)
    table = RunTable(os.path.join(output, "lbm_throat_error.csv"), FIELDS)
    rows = table.rows
    for phi in ZICK_HOMSY:
        for side in SIDES:
            if table.find(lambda r: float(r["phi"]) == phi and int(r["side"]) == side):
                continue
            row = {"phi": phi, "side": side, **run(build, work, phi, side)}
            table.add(row)
            print(f"phi {phi} side {side}: throat {row['throat_width']:.1f} voxels, "
                  f"error {100 * row['relative_error']:+.2f}%", flush=True)

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for phi in ZICK_HOMSY:
        points = sorted((float(r["throat_width"]), 100 * float(r["relative_error"]))
                        for r in rows if float(r["phi"]) == phi)
        ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=f"$\\phi$ = {phi}")
    for sign in (-1, 1):
        ax.axhline(sign * 100 * THRESHOLD, color="grey", ls=":")
    # The bands of lbm/permeability.hpp (kCoarseThroatWidth, kResolvedThroatWidth).
    ax.axvline(6.0, color="tab:red", ls="--", label="below 6 voxels: warned, errors to 65%")
    ax.axvline(17.0, color="tab:orange", ls="--", label="below 17 voxels: warned, errors to 8%")
    ax.set_xscale("log")
    ax.set_xlabel("narrowest throat along the flow [voxels]")
    ax.set_ylabel("K$_{11}$ / K(Zick & Homsy) - 1 [%]")
    ax.set_title("Simple cubic sphere arrays (Zick & Homsy), periodic body force, TRT")
    ax.text(0.02, 0.03, "dotted: $\\pm$2%", transform=ax.transAxes, fontsize=8)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(output, "lbm_throat_error.png"), dpi=120)


if __name__ == "__main__":
    main_guarded(main)
