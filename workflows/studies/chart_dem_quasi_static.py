#!/usr/bin/python3
"""Convergence of athermal quasi-static loading (docs/charts/dem_quasi_static.png, .csv).

Loads each prepared assembly (one per realisation) to FINAL_STRAIN in the quasi-static mode
(dem.load.quasi_static: each strain increment one affine step of the cell, then the FIRE
minimiser to an unbalanced-force ratio below dem.load.increment_tolerance) for three increments
over a decade (1e-4, 3e-5, 1e-5) and three tolerances (1e-2, OVAL's, 1e-3 and 1e-4), and continuously at
I = 1e-3, 1e-4 and 1e-5 (the slow physical limit). It draws (sigma11 - sigma33)/p,
(sigma22 - sigma33)/p and the volumetric strain against the axial strain, each the mean over the
realisations, and compares every setting with the next finer one. Rule for the defaults: the
coarsest setting whose (sigma11 - sigma33)/p agrees within 2% (mean over the strain, relative)
and whose volumetric strain agrees within 0.1% (absolute, largest difference) with the next finer
setting. Finished runs in the work folder are reused; JOBS runs go side by side. With
QS_FINISHED_ONLY=1 nothing runs: the chart draws the finished runs and compares settings on the
realisations both finished (the legend names a setting with fewer).

usage: chart_dem_quasi_static.py ANISO_DEM WORK OUTPUT FINAL_STRAIN JOBS PREPARED.h5...
"""
import concurrent.futures
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from runner import cached_load, finished_load, main_guarded  # noqa: E402
from readers import read_history  # noqa: E402
from load_convergence import COMPARE_FROM  # noqa: E402

INCREMENTS = [1e-4, 3e-5, 1e-5]
TOLERANCES = [1e-2, 1e-3, 1e-4]
RATES = [1e-3, 1e-4, 1e-5]
QUASI_STATIC = ["dem.load.quasi_static=true", "dem.equilibrium.method=fire", "dem.equilibrium.at_checkpoints=false",
                "dem.load.checkpoint_strains=[]"]
CONTINUOUS = ["dem.load.increment=0", "dem.equilibrium.at_checkpoints=false", "dem.load.checkpoint_strains=[]"]


def settings():
    """(label, key, aniso-dem settings) of every run kind, quasi-static first."""
    runs = [(f"quasi-static, increment {d:g}, tolerance {t:g}", ("qs", d, t),
             QUASI_STATIC + [f"dem.load.increment={d}", f"dem.load.increment_tolerance={t}"])
            for t in TOLERANCES for d in INCREMENTS]
    runs += [(f"continuous, I = {i:g}", ("rate", i), CONTINUOUS + [f"dem.load.inertial_number={i}"]) for i in RATES]
    return runs


def folder_of(work, key, realisation):
    name = f"qs_d{key[1]:g}_t{key[2]:g}" if key[0] == "qs" else f"rate_I{key[1]:g}"
    return f"{work}/{name}_r{realisation}"


def ratios(h):
    """Axial strain (compression positive), (s11 - s33)/p, (s22 - s33)/p (compression-positive
    stresses) and the volumetric strain (dilation positive)."""
    p = h["p"]
    return (-h["strain_11"], (h["stress_33"] - h["stress_11"]) / p, (h["stress_33"] - h["stress_22"]) / p,
            h["volumetric_strain"])


def on_grid(h, grid):
    strain, r13, r23, volume = ratios(h)
    return np.interp(grid, strain, r13), np.interp(grid, strain, r23), np.interp(grid, strain, volume)


def steps_of(folder):
    """Time steps of the loading, from its history's step column (docs/formats/history.md)."""
    step = read_history(f"{folder}/history.h5")["step"]
    return int(step[-1] - step[0])


def main(binary, work, out, final_strain, jobs, prepared):
    grid = np.linspace(0, final_strain, 201)
    kinds = settings()
    runs = {}
    if os.environ.get("QS_FINISHED_ONLY") == "1":
        # A partial study: only the runs already finished, compared on the realisations both have.
        for _, key, _ in kinds:
            for r in range(len(prepared)):
                if (run := finished_load(folder_of(work, key, r), final_strain)) is not None:
                    runs[(key, r)] = run
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            tasks = {(key, r): pool.submit(cached_load, binary, path, folder_of(work, key, r), options, final_strain)
                     for _, key, options in kinds for r, path in enumerate(prepared)}
        runs = {k: t.result() for k, t in tasks.items()}
    kinds = [k for k in kinds if any((k[1], r) in runs for r in range(len(prepared)))]
    curves, costs, have = {}, {}, {}
    for label, key, _ in kinds:
        have[key] = [r for r in range(len(prepared)) if (key, r) in runs]
        curves[key] = {r: np.array(on_grid(runs[(key, r)][0], grid)) for r in have[key]}  # quantity, strain
        costs[key] = (np.mean([runs[(key, r)][1] for r in have[key]]),
                      np.mean([steps_of(folder_of(work, key, r)) for r in have[key]]))

    fig, axes = plt.subplots(1, 3, figsize=(17, 5))
    for label, key, _ in kinds:
        mean = np.mean([curves[key][r] for r in have[key]], axis=0)
        label = f"{label} ({len(have[key])} realisations)" if len(have[key]) < len(prepared) else label
        # Quasi-static by tolerance, coarsest dash-dot to finest solid; continuous dotted.
        style = ["-.", "--", "-"][TOLERANCES.index(key[2])] if key[0] == "qs" else ":"
        for q in range(3):
            axes[q].plot(100 * grid, mean[q] * (100 if q == 2 else 1), style, lw=1.2, label=label)
    titles = [r"$(\sigma_{11} - \sigma_{33})/p$", r"$(\sigma_{22} - \sigma_{33})/p$",
              r"volumetric strain $\varepsilon_v$ (%), dilation positive"]
    for ax, title in zip(axes, titles):
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.set_title(title)
        ax.grid(alpha=0.3)
    axes[2].legend(fontsize=6)
    fig.suptitle(f"Quasi-static loading against its increment and tolerance, and continuous loading: "
                 f"mean of {len(prepared)} realisations")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_quasi_static.png", dpi=110)

    keep = grid >= COMPARE_FROM
    rows = []

    def compare(coarse, fine, what):
        # Per realisation both ran: the mean relative difference of (s11 - s33)/p past COMPARE_FROM,
        # the mean difference of (s22 - s33)/p, the largest absolute difference of the volumetric
        # strain; then the mean over those realisations.
        if coarse not in curves or fine not in curves:
            return
        shared = [r for r in have[coarse] if r in have[fine]]
        if not shared:
            return
        a, b = curves[coarse], curves[fine]
        q13 = np.mean([abs(a[r][0, keep].mean() - b[r][0, keep].mean()) / b[r][0, keep].mean() for r in shared])
        q23 = np.mean([abs(a[r][1, keep].mean() - b[r][1, keep].mean()) for r in shared])
        dv = np.mean([np.max(np.abs(a[r][2, keep] - b[r][2, keep])) for r in shared])
        rows.append({"comparison": what, "realisations": len(shared),
                     "ratio13_coarse": f"{np.mean([a[r][0, keep].mean() for r in shared]):.4f}",
                     "ratio13_fine": f"{np.mean([b[r][0, keep].mean() for r in shared]):.4f}",
                     "ratio13_mean_rel": f"{q13:.4f}", "ratio23_mean_abs": f"{q23:.4f}",
                     "volumetric_max_abs": f"{dv:.5f}", "within_rule": int(q13 <= 0.02 and dv <= 0.001),
                     "coarse_wall_s": f"{costs[coarse][0]:.1f}", "coarse_steps": f"{costs[coarse][1]:.0f}"})

    for t in TOLERANCES:
        for coarse, fine in zip(INCREMENTS[:-1], INCREMENTS[1:]):
            compare(("qs", coarse, t), ("qs", fine, t), f"increment {coarse:g} vs {fine:g}, tolerance {t:g}")
    for d in INCREMENTS:
        for coarse, fine in zip(TOLERANCES[:-1], TOLERANCES[1:]):
            compare(("qs", d, coarse), ("qs", d, fine), f"tolerance {coarse:g} vs {fine:g}, increment {d:g}")
    for coarse, fine in zip(RATES[:-1], RATES[1:]):
        compare(("rate", coarse), ("rate", fine), f"continuous I = {coarse:g} vs {fine:g}")
    slowest = [key for _, key, _ in kinds if key[0] == "rate"][-1:]
    for _, key, _ in kinds:
        if key[0] == "qs" and slowest:
            compare(key, slowest[0], f"quasi-static {key[1]:g}/{key[2]:g} vs continuous I = {slowest[0][1]:g}")
    with open(f"{out}/dem_quasi_static.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    with open(f"{out}/dem_quasi_static_costs.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["setting", "realisations", "wall_s", "steps", "ratio13_mean", "ratio23_mean",
                         "volumetric_final"])
        for label, key, _ in kinds:
            mean = np.mean([curves[key][r] for r in have[key]], axis=0)
            writer.writerow([label, len(have[key]), f"{costs[key][0]:.1f}", f"{costs[key][1]:.0f}",
                             f"{mean[0, keep].mean():.4f}", f"{mean[1, keep].mean():.4f}", f"{mean[2, -1]:.5f}"])
    for row in rows:
        print(row)


if __name__ == "__main__":
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), int(sys.argv[5]), sys.argv[6:])
