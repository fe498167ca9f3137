#!/usr/bin/python3
"""Time step against accuracy for ovoids (docs/charts/dem_time_step_ovoid.png, .csv).

Until 2026-12-02 the step was a fraction of the Rayleigh step of the smallest particle's
half-height (alpha R); since then of the sphere of the same volume (R_v), 1.34x longer for
alpha = 0.625 and about 1.5x for alpha = 0.5. This chart loads one prepared ovoid assembly
(continuous, I = 1e-3, to 5%) at steps from 0.25 t_R(alpha R) to 1.0 t_R(R_v), in pairs whose
steps differ by 2-5% (the chaotic floor: two runs of the same physics part at once), and
compares every run with the smallest step. The servo period (control_interval x step) is held
near 5e-8 s except in the new default (0.5 t_R(R_v) with the default interval of 4: 2 t_R(R_v),
6.6e-8 s) and at 1.0 t_R(R_v). Times are in seconds: for the demo's alpha = 0.625 assembly t_R(alpha R) = 2.48e-8 s
and t_R(R_v) = 3.32e-8 s. Finished runs are reused.

usage: chart_dem_time_step_ovoid.py ANISO_DEM PREPARED.h5 WORK_FOLDER OUTPUT_FOLDER
"""
import concurrent.futures
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from runner import cached_load, main_guarded  # noqa: E402
from load_convergence import compare, curves, label_curve_axes  # noqa: E402

FINAL_STRAIN = 0.05
# name, time step [s], control interval, the run it pairs with for the floor (or None), label
RUNS = [
    ("A", 6.2e-9, 8, None, "0.25 t_R(alpha R): reference"),
    ("F", 6.5e-9, 8, "A", "floor pair of A"),
    ("B", 1.24e-8, 4, None, "0.5 t_R(alpha R): the old default"),
    ("B2", 1.2e-8, 4, "B", "floor pair of B"),
    ("C3", 1.66e-8, 3, None, "0.5 t_R(R_v)"),
    ("G", 1.6e-8, 3, "C3", "floor pair of C3"),
    ("C", 1.66e-8, 4, None, "0.5 t_R(R_v), interval 4: the new default (servo period 6.6e-8 s)"),
    ("D", 3.32e-8, 2, None, "1.0 t_R(R_v), servo period 6.6e-8 s"),
    ("H", 3.2e-8, 2, "D", "floor pair of D"),
]


def main(binary, prepared, work, out):
    with h5py.File(prepared, "r") as f:
        n_particles = f["particles/id"].shape[0]
        alpha = float(f["particles/aspect_ratio"][0])
    common = ["dem.load.inertial_number=1e-3", "dem.load.increment=0", "dem.equilibrium.at_checkpoints=false",
              f"dem.load.checkpoint_strains=[{FINAL_STRAIN}]"]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {name: pool.submit(cached_load, binary, prepared, f"{work}/{name}",
                                     common + [f"dem.integration.time_step={dt}",
                                               f"dem.integration.control_interval={interval}"], FINAL_STRAIN)
                   for name, dt, interval, _, _ in RUNS}
        runs = {name: future.result() for name, future in futures.items()}
    reference = runs["A"][0]
    rows = []
    for name, dt, interval, pair, label in RUNS:
        h, wall = runs[name]
        steps = h["step"][-1] - h["step"][0]
        versus_reference = compare(h, reference, FINAL_STRAIN) if name != "A" else (0.0, 0.0, 0.0)
        versus_pair = compare(h, runs[pair][0], FINAL_STRAIN) if pair else (np.nan,) * 3
        rows.append((name, dt, interval, steps * n_particles, wall) + tuple(versus_reference) + tuple(versus_pair)
                    + (label,))
    fig, axes = plt.subplots(1, 3, figsize=(17, 4.6))
    for name, dt, interval, pair, label in RUNS:
        if pair:
            continue
        strain, q_over_p, volumetric = curves(runs[name][0])
        axes[0].plot(100 * strain, q_over_p, lw=1, label=f"{dt:.3g} s: {label}")
        axes[1].plot(100 * strain, 100 * volumetric, lw=1, label=f"{dt:.3g} s: {label}")
    for r in rows:
        if r[0] == "A":
            continue
        floor = r[0] in {"F", "B2", "G", "H"}
        axes[2].plot(r[1], 100 * r[6], "s" if floor else "o", color="tab:blue", mfc="none" if floor else None)
        axes[2].plot(r[1], 100 * r[7], "s" if floor else "o", color="tab:red", mfc="none" if floor else None)
        axes[2].annotate(r[0], (r[1], 100 * r[6]), fontsize=7)
    axes[2].set_xlabel("time step (s)")
    axes[2].set_ylabel("vs the reference: q/p worst 1% bin (blue), eps_v (red), %")
    axes[2].set_title("open squares: a floor pair's own step (same physics)", fontsize=9)
    label_curve_axes(axes)
    fig.suptitle(f"Time step against accuracy: {n_particles} ovoids of alpha = {alpha:g}, I = 1e-3, continuous loading")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_time_step_ovoid.png", dpi=110)
    with open(f"{out}/dem_time_step_ovoid.csv", "w") as csv:
        csv.write("run,time_step_s,control_interval,particle_steps,wall_seconds,mean_q_over_p_vs_reference,"
                  "worst_bin_q_over_p_vs_reference,volumetric_vs_reference,mean_q_over_p_vs_pair,"
                  "worst_bin_q_over_p_vs_pair,volumetric_vs_pair,label\n")
        for r in rows:
            csv.write("%s,%.4g,%d,%.4g,%.1f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,%s\n" % r)
            print("%-3s %.3g s interval %d: %.3g particle-steps; vs reference mean q/p %.2f%%, worst bin %.2f%%, "
                  "eps_v %.3f%%; vs its pair %.2f%%, %.2f%%, %.3f%% (%s)" % (
                      r[0], r[1], r[2], r[3], 100 * r[5], 100 * r[6], 100 * r[7], 100 * r[8], 100 * r[9],
                      100 * r[10], r[11]))


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main_guarded(main, *sys.argv[1:])
