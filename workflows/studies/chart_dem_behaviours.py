#!/usr/bin/python3
"""The named loading behaviours (dem.load.behaviour) on the same prepared assemblies, from
workflows/studies/load_behaviours.py's WORK/results/<assembly>_<behaviour>.csv (docs/methods/dem.md,
"The behaviours on the paper's assemblies").

Writes OUTPUT/dem_behaviours_curves.csv (every run on one strain grid, so the chart can be redrawn
from the committed file), OUTPUT/dem_behaviours.csv (per run: the peak of (sigma11 - sigma33)/p and
its strain, then the ratio, eps_v and Z at 0.5-20%) and OUTPUT/dem_behaviours.png (a row per
assembly: the ratio, eps_v and Z against strain).

usage: chart_dem_behaviours.py RESULTS OUTPUT     (load_behaviours.py's WORK/results)
       chart_dem_behaviours.py --from-curves OUTPUT
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from chart_dem_dempla import names_in, on_grid, read_curves, read_runs, summary, write_curves  # noqa: E402

NAME = "dem_behaviours"
BEHAVIOURS = {
    "inertial": ("inertial (I = 1e-3, contact damping)", "C0", "-"),
    "oval": ("oval (DEMPLA's body damping, spin x6)", "C3", "-"),
    "quasi_static": ("quasi_static (3e-5, minimised to 1e-3)", "k", "-"),
    "increments": ("OVAL's increments (1e-4 relaxed to 1e-2)", "C4", ":"),
}
COLUMNS = {"q13": "(sigma11 - sigma33)/p", "eps_v": "eps_v [%] (dilation +)", "coordination": "Z (all particles)"}


def split(name):
    """'ovoids-0.5_quasi_static' -> ('ovoids-0.5', 'quasi_static')."""
    for behaviour in BEHAVIOURS:
        if name.endswith("_" + behaviour):
            return name[: -len(behaviour) - 1], behaviour
    raise SystemExit(f"chart_dem_behaviours.py: run '{name}' names no behaviour of {list(BEHAVIOURS)}")


def aspect_order(assembly):
    """'spheres' first, then 'ovoids-<alpha>' by falling alpha."""
    try:
        return -float(assembly.split("-")[-1])
    except ValueError:
        return -1.0 if assembly == "spheres" else 0.0


def chart(grid, path):
    # Spheres first, then flatter and flatter ovoids.
    assemblies = sorted({split(n)[0] for n in names_in(grid)}, key=aspect_order)
    handles = {}
    strain = 100 * grid["strain"]
    fig, axes = plt.subplots(len(assemblies), len(COLUMNS), figsize=(13, 3.4 * len(assemblies)), squeeze=False)
    for row, assembly in zip(axes, assemblies):
        for ax, (q, title) in zip(row, COLUMNS.items()):
            for name in names_in(grid):
                owner, behaviour = split(name)
                if owner != assembly:
                    continue
                label, colour, style = BEHAVIOURS[behaviour]
                (handles[behaviour],) = ax.plot(strain, grid[f"{name}:{q}"] * (100 if q == "eps_v" else 1), style,
                                                color=colour, label=label)
            ax.set_title(f"{assembly}: {title}", fontsize=10)
            ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("compressive strain -eps11 [%]")
    shown = [b for b in BEHAVIOURS if b in handles]
    fig.legend([handles[b] for b in shown], [BEHAVIOURS[b][0] for b in shown], loc="lower center", ncol=4, fontsize=9)
    fig.suptitle("Loading behaviours on the same 1000-particle paper-config assemblies (biaxial, constant p)")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(path, dpi=100)


def main(argv):
    if len(argv) != 3:
        raise SystemExit(__doc__)
    output = argv[2]
    if argv[1] == "--from-curves":
        grid = read_curves(f"{output}/{NAME}_curves.csv")
    else:
        grid = on_grid(read_runs(argv[1]))
        write_curves(grid, f"{output}/{NAME}_curves.csv")
    summary(grid, f"{output}/{NAME}.csv")
    chart(grid, f"{output}/{NAME}.png")


if __name__ == "__main__":
    main(sys.argv)
