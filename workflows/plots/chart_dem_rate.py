#!/usr/bin/python3
"""Speed/accuracy chart of the DEM loading rate (docs/charts/dem_rate.png).

Loads one prepared assembly in biaxial plane strain at several inertial numbers
(and contact damping ratios), then charts (s11 - s33)/p and volumetric strain
against strain, and the cost (particle-steps, wall time) against the deviation
from the slowest run. The numbers go to dem_rate.csv beside the figure.

usage: chart_dem_rate.py ANISO_DEM PREPARED.h5 WORK_FOLDER OUTPUT_FOLDER [FINAL_STRAIN]
"""
import os
import subprocess
import sys
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402

INERTIAL_NUMBERS = [1e-2, 3e-3, 1e-3, 3e-4]
DAMPING_RATIOS = [0.0, 0.05, 0.3]
# The reference: the slowest rate, with the default damping only (it is the costliest run).
REFERENCE = (1e-4, 0.05)


def run(binary, prepared, folder, inertial, damping, final_strain):
    """Loads at one rate; a finished run in `folder` (same final strain) is reused, not redone."""
    try:
        h = read_history(f"{folder}/history.h5")
        if abs(-h["strain_11"][-1] - final_strain) < 1e-3 * final_strain and os.path.exists(f"{folder}/wall.txt"):
            return h, float(open(f"{folder}/wall.txt").read())
    except OSError:
        pass
    start = time.monotonic()
    subprocess.run([binary, "load", "--input", prepared, "--log-level", "warn",
                    "--set", f"dem.output_dir={folder}", "--set", f"dem.load.inertial_number={inertial}",
                    "--set", f"dem.integration.damping={damping}", "--set", f"dem.load.final_strain={final_strain}",
                    "--set", f"dem.load.history_interval={final_strain / 100}"], check=True)
    wall = time.monotonic() - start
    with open(f"{folder}/wall.txt", "w") as out:
        out.write(f"{wall}\n")
    return read_history(f"{folder}/history.h5"), wall


def curves(h):
    strain = -h["strain_11"]
    ratio = (h["stress_33"] - h["stress_11"]) / h["p"]
    return strain, ratio, h["volumetric_strain"]


def deviation(h, reference):
    """Mean absolute difference of the stress ratio from the reference curve, on the reference's strains."""
    strain, ratio, _ = curves(h)
    ref_strain, ref_ratio, _ = curves(reference)
    return float(np.mean(np.abs(np.interp(ref_strain, strain, ratio) - ref_ratio)))


def main(binary, prepared, work, out, final_strain):
    with h5py.File(prepared, "r") as f:
        n_particles = f["particles/id"].shape[0]
    runs = {}
    for inertial, damping in [REFERENCE] + [(i, d) for d in DAMPING_RATIOS for i in INERTIAL_NUMBERS]:
        folder = f"{work}/I{inertial:g}_d{damping:g}"
        subprocess.run(["mkdir", "-p", folder], check=True)
        h, wall = run(binary, prepared, folder, inertial, damping, final_strain)
        runs[(inertial, damping)] = (h, wall)
    reference = runs[REFERENCE][0]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    rows = []
    for (inertial, damping), (h, wall) in sorted(runs.items()):
        strain, ratio, volumetric = curves(h)
        steps = h["step"][-1] - h["step"][0]
        style = {0.0: ":", 0.05: "-", 0.3: "--"}[damping]
        label = f"I={inertial:g}, damping {damping:g}"
        if damping == 0.05:
            axes[0].plot(100 * strain, ratio, style, label=label)
            axes[1].plot(100 * strain, 100 * volumetric, style, label=label)
        dev = deviation(h, reference)
        axes[2].loglog(max(dev, 1e-4), steps * n_particles, "o" if damping == 0.05 else "x")
        axes[2].annotate(f"{inertial:g}/{damping:g}", (max(dev, 1e-4), steps * n_particles), fontsize=7)
        servo = np.abs(h["servo_error"][strain > 0.001])
        rows.append([inertial, damping, steps * n_particles, wall, dev, np.median(servo), servo.max(), ratio.max()])
    axes[0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[1].set_ylabel("volumetric strain (%)")
    for ax in axes[:2]:
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[2].set_xlabel(f"mean |deviation| of the stress ratio from I={REFERENCE[0]:g}, damping {REFERENCE[1]:g}")
    axes[2].set_ylabel("cost (particle-steps)")
    axes[2].grid(alpha=0.3, which="both")
    fig.suptitle(f"DEM loading rate and damping: {n_particles} spheres (labels: I/damping)")
    fig.tight_layout()
    fig.savefig(f"{out}/dem_rate.png", dpi=110)
    np.savetxt(f"{out}/dem_rate.csv", np.array(rows), delimiter=",", comments="",
               header="inertial_number,damping,particle_steps,wall_seconds,mean_ratio_deviation,"
                      "servo_error_median,servo_error_max,peak_ratio")
    for row in rows:
        print("I=%-7g damping=%-5g cost=%.3g particle-steps wall=%.1f s deviation=%.4f servo median=%.4f max=%.4f "
              "peak=%.3f" % tuple(row))


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]) if len(sys.argv) == 6 else 0.05)
