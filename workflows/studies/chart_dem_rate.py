#!/usr/bin/python3
"""Rate convergence of the DEM loading (docs/charts/dem_rate.png, dem_rate.csv).

Loads one prepared assembly continuously (dem.load.increment = 0) in biaxial
plane strain at constant p at four inertial numbers over 1.5 decades, at two
levels of viscous contact damping (dem.integration.damping). At the default
damping every rate is run three times, at time steps of 0.49, 0.50 and 0.51 of
the Rayleigh step: the same physics, so their spread is the chaotic floor of
one realization. Each rate's mean curve is compared with the next slower
rate's (mean q/p within 2 %, volumetric strain within 0.1 %
absolute), beside the floor. Two runs go at once (one per core). A finished
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

from runner import cached_load, main_guarded  # noqa: E402
from load_convergence import COMPARE_FROM, curves  # noqa: E402

INERTIAL_NUMBERS = [3e-3, 1e-3, 3e-4, 1e-4]
DEFAULT_DAMPING = 0.05
OTHER_DAMPING = 0.2
STEP_FRACTIONS = [0.5, 0.49, 0.51]  # replicates at the default damping; the others run at 0.5 only
SLOW_RATES = [3e-5, 1e-5]  # one run each at the default damping, to half the final strain (the trend below 1e-4)


def folder_of(work, inertial, damping, fraction):
    return f"{work}/I{inertial:g}_d{damping:g}_f{fraction:g}"


def settings_of(inertial, damping, fraction):
    return [f"dem.load.inertial_number={inertial}", f"dem.integration.damping={damping}",
            f"dem.integration.time_step_fraction={fraction}", "dem.load.increment=0",
            "dem.integration.global_damping=0", "dem.load.checkpoint_strains=[]"]


def on_grid(h, grid):
    strain, q_over_p, volumetric = curves(h)
    return np.interp(grid, strain, q_over_p), np.interp(grid, strain, volumetric)


def summarize(runs, grid):
    """Mean curves over the replicates, each replicate's mean q/p and final eps_v, and the floor: the
    largest difference of one replicate from another (mean q/p relative, eps_v absolute along the path)."""
    q = np.array([on_grid(h, grid)[0] for h, _ in runs])
    v = np.array([on_grid(h, grid)[1] for h, _ in runs])
    means = q.mean(axis=1)
    floor_q = (means.max() - means.min()) / means.mean() if len(runs) > 1 else float("nan")
    floor_v = max((np.max(np.abs(a - b)) for a in v for b in v), default=0.0) if len(runs) > 1 else float("nan")
    return q.mean(axis=0), v.mean(axis=0), floor_q, floor_v


def main(binary, prepared, work, out, final_strain):
    with h5py.File(prepared, "r") as f:
        n_particles = f["particles/id"].shape[0]
    jobs = [(i, DEFAULT_DAMPING, s) for s in STEP_FRACTIONS for i in INERTIAL_NUMBERS]
    jobs += [(i, OTHER_DAMPING, 0.5) for i in INERTIAL_NUMBERS]
    slow_jobs = [(i, DEFAULT_DAMPING, 0.5) for i in SLOW_RATES]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {j: pool.submit(cached_load, binary, prepared, folder_of(work, *j), settings_of(*j), final_strain)
                   for j in jobs}
        slow_futures = {j: pool.submit(cached_load, binary, prepared, folder_of(work, *j), settings_of(*j),
                                       final_strain / 2) for j in slow_jobs}
        runs = {j: f.result() for j, f in futures.items()}
        slow = {j: f.result() for j, f in slow_futures.items()}
    grid = np.linspace(COMPARE_FROM, final_strain, 400)
    fig, axes = plt.subplots(1, 4, figsize=(21, 4.8))
    colours = dict(zip(INERTIAL_NUMBERS, ["tab:red", "tab:orange", "tab:green", "tab:blue"]))
    rows = []
    for damping in (DEFAULT_DAMPING, OTHER_DAMPING):
        summary = {}
        for inertial in INERTIAL_NUMBERS:
            group = [runs[j] for j in jobs if j[0] == inertial and j[1] == damping]
            summary[inertial] = summarize(group, grid) + (group,)
        for inertial in INERTIAL_NUMBERS:
            q, v, floor_q, floor_v, group = summary[inertial]
            steps = np.mean([h["step"][-1] - h["step"][0] for h, _ in group])
            wall = np.median([w for _, w in group])
            style = "-" if damping == DEFAULT_DAMPING else ":"
            label = f"I = {inertial:g}, contact damping {damping:g}" + (f" ({len(group)} runs)" if len(group) > 1 else "")
            axes[0].plot(100 * grid, q, style, color=colours[inertial], label=label, lw=1.2)
            axes[1].plot(100 * grid, 100 * v, style, color=colours[inertial], label=label, lw=1.2)
            slower = [i for i in INERTIAL_NUMBERS if i < inertial]
            dq = dv = float("nan")
            if slower:
                q_ref, v_ref = summary[max(slower)][:2]
                dq = abs(q.mean() - q_ref.mean()) / q_ref.mean()
                dv = float(np.max(np.abs(v - v_ref)))
                marker = "o" if damping == DEFAULT_DAMPING else "s"
                axes[2].loglog(dq, steps * n_particles, marker, color=colours[inertial])
                axes[3].loglog(dv, steps * n_particles, marker, color=colours[inertial])
            if len(group) > 1:  # the floor: how far apart three runs of the same physics land
                axes[2].loglog(floor_q, steps * n_particles, "|", color=colours[inertial], ms=14, mew=2)
                axes[3].loglog(floor_v, steps * n_particles, "|", color=colours[inertial], ms=14, mew=2)
            uf = np.median(np.concatenate([h["unbalanced_force_ratio"][curves(h)[0] > COMPARE_FROM]
                                           for h, _ in group]))
            rows.append([inertial, damping, len(group), steps * n_particles, wall, q.mean(), dq, floor_q,
                         100 * v[-1], dv, floor_v, uf])
    half = grid <= final_strain / 2 + 1e-12
    for (inertial, damping, fraction), (h, wall) in slow.items():
        q, v = on_grid(h, grid[half])
        axes[0].plot(100 * grid[half], q, "-", color="black", lw=0.8, alpha=0.5 if inertial < min(SLOW_RATES) * 2 else 0.9,
                     label=f"I = {inertial:g} (one run, to {50 * final_strain:g}%)")
        axes[1].plot(100 * grid[half], 100 * v, "-", color="black", lw=0.8,
                     alpha=0.5 if inertial < min(SLOW_RATES) * 2 else 0.9, label=f"I = {inertial:g} (one run)")
        steps = h["step"][-1] - h["step"][0]
        uf = np.median(h["unbalanced_force_ratio"][curves(h)[0] > COMPARE_FROM])
        rows.append([inertial, damping, 1, steps * n_particles, wall, q.mean(), float("nan"), float("nan"),
                     100 * v[-1], float("nan"), float("nan"), uf])
    for ax in axes[2:]:
        ax.plot([], [], "|", color="grey", ms=14, mew=2, label="spread of 3 runs at that rate (floor)")
        ax.set_ylabel("cost (particle-steps)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    axes[2].axvline(0.02, color="grey", ls="--")
    axes[3].axvline(0.001, color="grey", ls="--")
    axes[0].set_ylabel("q/p (mean of the runs)")
    axes[1].set_ylabel(r"volumetric strain $\varepsilon_v$ (%), dilation positive")
    for ax in axes[:2]:
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[2].set_xlabel("|mean q/p - that of the next slower rate| / mean q/p")
    axes[3].set_xlabel(r"largest |$\varepsilon_v$ - that of the next slower rate|")
    fig.suptitle(f"Rate convergence of biaxial loading at constant p: {n_particles} spheres, continuous loading "
                 f"(o: contact damping {DEFAULT_DAMPING:g}, s: {OTHER_DAMPING:g}; dashed: the goals)")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_rate.png", dpi=110)
    # The slow runs reach half the final strain: their mean q/p and final eps_v are over 0.5% .. that strain.
    np.savetxt(f"{out}/dem_rate.csv", np.array(rows), delimiter=",", comments="", fmt="%.6g",
               header="inertial_number,contact_damping,runs,particle_steps,wall_seconds,mean_q_over_p,"
                      "mean_q_over_p_vs_slower,mean_q_over_p_floor,final_volumetric_percent,"
                      "volumetric_vs_slower,volumetric_floor,unbalanced_force_ratio_median")
    for r in rows:
        print("I=%-7g damping=%-4g runs=%d cost=%.3g wall=%.0f s  q/p=%.4f  vs slower %.4f (floor %.4f)  "
              "ev_end=%.3f%%  vs slower %.4f (floor %.4f)  U_f %.2g" % tuple(r))


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]) if len(sys.argv) == 6 else 0.1)
