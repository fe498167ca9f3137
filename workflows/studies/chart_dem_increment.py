#!/usr/bin/python3
"""Convergence of OVAL-style incremental loading (docs/charts/dem_increment.png, .csv).

Loads one prepared assembly to FINAL_STRAIN in strain increments, each followed
by a relaxation to an unbalanced-force ratio below a tolerance
(dem.load.increment, dem.load.increment_tolerance), and compares settings that
differ in one thing: the increment (3e-4, 1e-4, 3e-5), the tolerance (1e-2, 1e-3),
the damping while relaxing (0.1, 0.3) and the rate within an increment
(I = 1e-3, 3e-3). Goal: q/p within 2 % and the volumetric strain
within 0.1 % (absolute) of the finer setting. Runs go one at a time; finished
runs in the work folder are reused.

usage: chart_dem_increment.py ANISO_DEM PREPARED.h5 WORK_FOLDER OUTPUT_FOLDER [FINAL_STRAIN [RATE_FOLDER]]
RATE_FOLDER: the work folder of chart_dem_rate.py, to draw its constant-rate runs beside these.
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from runner import cached_load, main_guarded  # noqa: E402
from readers import read_history  # noqa: E402
from load_convergence import compare, curves  # noqa: E402

# (increment, tolerance, damping while relaxing, inertial number within an increment)
DEFAULT = (1e-4, 1e-2, 0.1, 1e-3)
SETTINGS = [(3e-4, 1e-2, 0.1, 1e-3), DEFAULT, (3e-5, 1e-2, 0.1, 1e-3), (1e-4, 1e-3, 0.1, 1e-3),
            (1e-4, 1e-2, 0.3, 1e-3), (1e-4, 1e-2, 0.1, 3e-3)]
# (coarser or other setting, finer or reference setting, what is compared)
COMPARISONS = [((3e-4, 1e-2, 0.1, 1e-3), DEFAULT, "increment 3e-4 vs 1e-4"),
               (DEFAULT, (3e-5, 1e-2, 0.1, 1e-3), "increment 1e-4 vs 3e-5"),
               (DEFAULT, (1e-4, 1e-3, 0.1, 1e-3), "tolerance 1e-2 vs 1e-3"),
               (DEFAULT, (1e-4, 1e-2, 0.3, 1e-3), "relaxation damping 0.1 vs 0.3"),
               ((1e-4, 1e-2, 0.1, 3e-3), DEFAULT, "rate within an increment I = 3e-3 vs 1e-3")]


def folder_of(work, s):
    return f"{work}/d{s[0]:g}_t{s[1]:g}_z{s[2]:g}_I{s[3]:g}"



def main(binary, prepared, work, out, final_strain, rate_folder):
    with h5py.File(prepared, "r") as f:
        n_particles = f["particles/id"].shape[0]
    runs = {s: cached_load(binary, prepared, folder_of(work, s),
                           [f"dem.load.increment={s[0]}", f"dem.load.increment_tolerance={s[1]}",
                            f"dem.equilibrium.damping={s[2]}", f"dem.load.inertial_number={s[3]}"], final_strain)
            for s in SETTINGS}
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    for s, (h, _) in runs.items():
        strain, q, v = curves(h)
        label = f"increment {s[0]:g}, tolerance {s[1]:g}, damping {s[2]:g}, I {s[3]:g}"
        style = "-" if s[1:] == DEFAULT[1:] else "--"
        axes[0].plot(100 * strain, q, style, lw=1, label=label)
        axes[1].plot(100 * strain, 100 * v, style, lw=1, label=label)
    if rate_folder:
        for inertial in (1e-3, 1e-4):
            path = f"{rate_folder}/I{inertial:g}_g0/history.h5"
            if os.path.exists(path):
                strain, q, v = curves(read_history(path))
                keep = strain <= final_strain
                label = f"constant rate I = {inertial:g} (no increments)"
                axes[0].plot(100 * strain[keep], q[keep], ":", color="grey" if inertial == 1e-4 else "k", label=label)
                axes[1].plot(100 * strain[keep], 100 * v[keep], ":", color="grey" if inertial == 1e-4 else "k",
                             label=label)
    axes[0].set_ylabel("q/p")
    axes[1].set_ylabel(r"volumetric strain $\varepsilon_v$ (%), dilation positive")
    for ax in axes:
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=6)
    fig.suptitle(f"Incremental loading with relaxation after each increment: {n_particles} spheres")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_increment.png", dpi=110)
    rows = []
    for coarse, fine, what in COMPARISONS:
        dq, dbin, dv = compare(runs[coarse][0], runs[fine][0], final_strain)
        h = runs[coarse][0]
        steps = h["step"][-1] - h["step"][0]
        rows.append((what, *coarse, steps * n_particles, runs[coarse][1], dq, dbin, dv))
    with open(f"{out}/dem_increment.csv", "w") as csv:
        csv.write("comparison,increment,tolerance,relaxation_damping,inertial_number,particle_steps,wall_seconds,"
                  "mean_q_over_p_difference,worst_bin_q_over_p_difference,volumetric_difference\n")
        for row in rows:
            csv.write("%s,%g,%g,%g,%g,%.4g,%.1f,%.4f,%.4f,%.5f\n" % row)
            print("%-45s cost %.3g particle-steps, %.0f s: mean q/p %.2f%%, worst 1%% bin %.2f%%, eps_v %.3f%%" % (
                row[0], row[5], row[6], 100 * row[7], 100 * row[8], 100 * row[9]))


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6, 7):
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]) if len(sys.argv) > 5 else 0.05,
         sys.argv[6] if len(sys.argv) > 6 else "")
