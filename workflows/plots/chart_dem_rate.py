#!/usr/bin/python3
"""Rate convergence of the DEM loading (docs/charts/dem_rate.png, dem_rate.csv).

Loads one prepared assembly in biaxial plane strain at constant p at four
inertial numbers over 1.5 decades and two levels of global damping of the
fluctuating motion (dem.integration.global_damping), continuously (no
increments: dem.load.increment = 0), then compares each run with
the next slower one at the same damping (issue: q/p within 2 %, volumetric
strain within 0.1 % absolute). Two runs go at once (one per core). A finished
run in the work folder (same final strain) is reused, so an interrupted chart
continues where it stopped.

usage: chart_dem_rate.py ANISO_DEM PREPARED.h5 WORK_FOLDER OUTPUT_FOLDER [FINAL_STRAIN]
"""
import concurrent.futures
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from load_convergence import cached_load, compare, curves  # noqa: E402

INERTIAL_NUMBERS = [3e-3, 1e-3, 3e-4, 1e-4]
GLOBAL_DAMPING = [0.0, 0.1]


def folder_of(work, inertial, damping):
    return f"{work}/I{inertial:g}_g{damping:g}"



def main(binary, prepared, work, out, final_strain):
    with h5py.File(prepared, "r") as f:
        n_particles = f["particles/id"].shape[0]
    settings = [(i, d) for i in INERTIAL_NUMBERS for d in GLOBAL_DAMPING]  # fastest first
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {s: pool.submit(cached_load, binary, prepared, folder_of(work, *s),
                                  [f"dem.load.inertial_number={s[0]}", f"dem.integration.global_damping={s[1]}",
                                   "dem.load.increment=0"], final_strain) for s in settings}
        runs = {s: f.result() for s, f in futures.items()}
    fig, axes = plt.subplots(1, 4, figsize=(20, 4.6))
    rows = []
    colours = dict(zip(INERTIAL_NUMBERS, ["tab:red", "tab:orange", "tab:green", "tab:blue"]))
    for (inertial, damping), (h, wall) in sorted(runs.items(), key=lambda item: (item[0][1], -item[0][0])):
        strain, q_over_p, volumetric = curves(h)
        steps = h["step"][-1] - h["step"][0]
        style = "-" if damping == GLOBAL_DAMPING[-1] else ":"
        label = f"I = {inertial:g}, global damping {damping:g}"
        axes[0].plot(100 * strain, q_over_p, style, color=colours[inertial], label=label, lw=1)
        axes[1].plot(100 * strain, 100 * volumetric, style, color=colours[inertial], label=label, lw=1)
        slower = [i for i in INERTIAL_NUMBERS if i < inertial]
        dq = dbin = dv = float("nan")
        if slower:
            dq, dbin, dv = compare(h, runs[(max(slower), damping)][0])
            axes[2].loglog(dq, steps * n_particles, "o" if damping else "x", color=colours[inertial])
            axes[3].loglog(dv, steps * n_particles, "o" if damping else "x", color=colours[inertial])
        servo = np.abs(h["servo_error"][strain > 0.001])
        peak = int(np.argmax(q_over_p))
        rows.append([inertial, damping, steps * n_particles, wall, dq, dbin, dv, q_over_p[peak], 100 * strain[peak],
                     100 * volumetric[-1], np.median(servo), np.median(h["unbalanced_force_ratio"][strain > 0.001])])
    axes[0].set_ylabel("q/p")
    axes[1].set_ylabel(r"volumetric strain $\varepsilon_v$ (%), dilation positive")
    for ax in axes[:2]:
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[2].axvline(0.02, color="grey", ls="--")
    axes[3].axvline(0.001, color="grey", ls="--")
    axes[2].set_xlabel("|mean q/p - mean q/p of the next slower rate| / mean q/p")
    axes[3].set_xlabel(r"largest |$\varepsilon_v$ - $\varepsilon_v$ of the next slower rate|")
    for ax in axes[2:]:
        ax.set_ylabel("cost (particle-steps)")
        ax.grid(alpha=0.3, which="both")
    fig.suptitle(f"Rate convergence of biaxial loading at constant p: {n_particles} spheres "
                 f"(o: global damping {GLOBAL_DAMPING[-1]:g}, x: none; dashed: the tolerances)")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_rate.png", dpi=110)
    np.savetxt(f"{out}/dem_rate.csv", np.array(rows), delimiter=",", comments="", fmt="%.6g",
               header="inertial_number,global_damping,particle_steps,wall_seconds,mean_q_over_p_vs_slower,"
                      "worst_bin_q_over_p_vs_slower,volumetric_vs_slower,peak_q_over_p,peak_strain_percent,final_volumetric_percent,"
                      "servo_error_median,unbalanced_force_ratio_median")
    for row in rows:
        print("I=%-7g global damping=%-4g cost=%.3g particle-steps wall=%.0f s dq/p=%.4f worst bin %.4f dev=%.5f peak q/p=%.3f "
              "at %.2f%% final ev=%.3f%% servo=%.2g ufr=%.2g" % tuple(row))


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]) if len(sys.argv) == 6 else 0.1)
