#!/usr/bin/python3
"""aniso beside DEMPLA (Kuhn's OVAL successor) on one assembly (DEMPLA's Dsphere_1800, or aniso's
1000 alpha = 0.625 ovoids): (sigma11 - sigma33)/p,
(sigma22 - sigma33)/p, eps_v and Z against strain for each run of tests/dem/peer/dempla_biaxial.sh
(docs/validation.md, "DEM against DEMPLA").

Writes OUTPUT/NAME_curves.csv (NAME: dem_dempla_spheres unless given) (every run on one strain grid, so the chart can be
redrawn from the committed file), OUTPUT/NAME.csv (per run: the peak and its strain,
(sigma11 - sigma33)/p, eps_v and Z at 0.5, 1, 2, 5, 10, 15 and 20% as far as the runs go) and OUTPUT/NAME.png.

usage: chart_dem_dempla.py RESULTS_DIRS OUTPUT [NAME]   (dempla_biaxial.sh's WORK/results, comma-separated)
       chart_dem_dempla.py --from-curves OUTPUT [NAME]  (redraw from the committed curves CSV)
"""
import csv
import glob
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "dempla_default": ("DEMPLA as its samples run (body damping 3%/5%)", "C3", "-"),
    "dempla_no_body": ("DEMPLA set as aniso (contact damping, no body damping)", "C1", "--"),
    "aniso_default": ("aniso, DEMPLA's inertial number", "C0", "-"),
    "aniso_halfwidth": ("aniso, DEMPLA's I, the paper configs' Hertz radius (halfwidth)", "C7", "-."),
    "aniso_body": ("aniso set as DEMPLA (body damping, no contact damping)", "C2", "--"),
    "aniso_body_spin": ("aniso set fully as DEMPLA (body damping, spin x6)", "C6", "--"),
    "aniso_oval": ("aniso, OVAL's increments (paper configs)", "C4", ":"),
    "aniso_qs": ("aniso, quasi-static (3e-5, minimised to 1e-3)", "k", "-"),
    "dempla_no_spin_damping": ("DEMPLA without its body damping of rotation", "C8", "-."),
    "dempla_slow": ("DEMPLA as its samples run, a tenth of the rate", "C5", "-"),
    "aniso_slow": ("aniso, a tenth of DEMPLA's inertial number", "C9", "-"),
    "aniso_body_spin_slow": ("aniso set fully as DEMPLA, a tenth of the rate", "C6", ":"),
}
TITLES = {
    "dem_dempla_spheres": "DEMPLA's Dsphere_1800 (D50 0.17 mm, e = 0.537 at 100 kPa)",
    "dem_dempla_spheres_rate": "DEMPLA's Dsphere_1800 (D50 0.17 mm, e = 0.537 at 100 kPa)",
    "dem_dempla_ovoids": "aniso's 1000 ovoids, alpha = 0.625 (paper-ovoids-0.625.toml; e = 0.555 at 100 kPa)",
    "dem_dempla_ovoids_rate": "aniso's 1000 ovoids, alpha = 0.625: DEMPLA's and aniso's rates and damping",
    "dem_dempla_ovoids_seed2": "aniso's 1000 ovoids, alpha = 0.625, seed 2 (e = 0.556 at 100 kPa): aniso's loadings",
}
QUANTITIES = ["q13", "q23", "eps_v", "coordination"]
GRID_STEP = 0.0025
REPORTED = [0.005, 0.01, 0.02, 0.05, 0.10, 0.15, 0.20]


def read_runs(results):
    """Every run CSV in the comma-separated result folders."""
    runs = {}
    paths = [p for folder in results.split(",") for p in sorted(glob.glob(f"{folder}/*.csv"))]
    for path in paths:
        name = os.path.basename(path)[:-4]
        data = np.genfromtxt(path, delimiter=",", names=True)
        runs[name] = {q: data[q] for q in ["strain"] + QUANTITIES}
    if not runs:
        raise SystemExit(f"chart_dem_dempla.py: no run CSVs in {results}")
    return runs


def on_grid(runs):
    """Every run averaged over bins of GRID_STEP of strain (one 1800-sphere path fluctuates from
    row to row), up to the largest final strain of the runs (NaN past a run's end)."""
    end = max(r["strain"][-1] for r in runs.values())
    edges = np.arange(0.0, end + 1e-12, GRID_STEP)
    grid = {"strain": 0.5 * (edges[1:] + edges[:-1])}
    grid["strain"] = np.r_[0.0, grid["strain"]]
    for name, r in runs.items():
        for q in QUANTITIES:
            values = [r[q][0]]
            for low, high in zip(edges[:-1], edges[1:]):
                inside = (r["strain"] > low) & (r["strain"] <= high)
                values.append(r[q][inside].mean() if inside.any() else np.nan)
            grid[f"{name}:{q}"] = np.array(values)
    return grid


def write_curves(grid, path):
    keys = list(grid)
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(keys)
        for row in zip(*(grid[k] for k in keys)):
            writer.writerow([f"{v:.6g}" for v in row])


def read_curves(path):
    data = np.genfromtxt(path, delimiter=",", names=True, deletechars="")
    return {k: data[k] for k in data.dtype.names}


def names_in(grid):
    return [k.split(":")[0] for k in grid if k.endswith(":q13")]


def summary(grid, path):
    """Per run: the peak of (sigma11 - sigma33)/p and its strain, then q13, eps_v and Z at the
    strains of REPORTED the runs reach (means over the GRID_STEP bin ending there)."""
    strain = grid["strain"]
    reported = [s for s in REPORTED if s <= strain[-1] + 0.5 * GRID_STEP]
    rows = []
    for name in names_in(grid):
        q13 = grid[f"{name}:q13"]
        k = int(np.nanargmax(q13))
        row = {"run": name, "peak_q13": f"{q13[k]:.3f}", "peak_strain": f"{strain[k]:.4f}"}
        for s in reported:
            j = int(np.argmin(abs(strain - (s - 0.5 * GRID_STEP))))
            row[f"q13_{100 * s:g}pc"] = f"{q13[j]:.3f}"
            row[f"eps_v_{100 * s:g}pc"] = f"{grid[f'{name}:eps_v'][j]:.4f}"
            row[f"Z_{100 * s:g}pc"] = f"{grid[f'{name}:coordination'][j]:.2f}"
        rows.append(row)
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    for row in rows:
        print(row)


def chart(grid, path, title):
    strain = 100 * grid["strain"]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    titles = {"q13": "(sigma11 - sigma33)/p", "q23": "(sigma22 - sigma33)/p",
              "eps_v": "volumetric strain [%] (dilation +)", "coordination": "Z (all particles)"}
    for ax, q in zip(axes.flat, QUANTITIES):
        for name in names_in(grid):
            label, colour, style = LABELS.get(name, (name, "k", "-"))
            values = grid[f"{name}:{q}"] * (100 if q == "eps_v" else 1)
            ax.plot(strain, values, style, color=colour, label=label)
        ax.set_ylabel(titles[q])
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("compressive strain -eps11 [%]")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(f"{title}: biaxial plane strain at constant p")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv):
    if len(argv) not in (3, 4):
        raise SystemExit(__doc__)
    output = argv[2]
    name = argv[3] if len(argv) == 4 else "dem_dempla_spheres"
    if argv[1] == "--from-curves":
        grid = read_curves(f"{output}/{name}_curves.csv")
    else:
        grid = on_grid(read_runs(argv[1]))
        write_curves(grid, f"{output}/{name}_curves.csv")
    summary(grid, f"{output}/{name}.csv")
    chart(grid, f"{output}/{name}.png", TITLES.get(name, name))


if __name__ == "__main__":
    main(sys.argv)
