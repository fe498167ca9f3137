#!/usr/bin/python3
"""Stress ratio and volume change of several loading runs of one assembly, side by side
(docs/charts/paper_spheres_protocols.png and .csv: the paper-size spheres loaded to 60%
continuously and in OVAL's relaxed increments).

Reads each run's history.h5 and writes the chart and, per run, the means over 1% strain
bins of (sigma_11 - sigma_33)/p, q/p, the volumetric strain, e and Z, with the smoothed
peak of the stress ratio.

usage: chart_loading_protocols.py OUTPUT_STEM LABEL=RUN_FOLDER [LABEL=RUN_FOLDER ...]  (split at the last =)
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from readers import read_history  # noqa: E402

BIN = 0.01  # strain per row of the table
SMOOTH = 0.005  # strain over which the stress ratio is averaged to find its peak


def binned(h):
    strain = -h["strain_11"]
    ratio = h["stress_ratio"]
    columns = {"stress_ratio": ratio, "q_over_p": h["q"] / h["p"], "volumetric_strain": h["volumetric_strain"],
               "void_ratio": h["void_ratio"], "coordination": h["coordination"]}
    edges = np.arange(0.0, strain.max() + 1e-12, BIN)
    rows = []
    for low, high in zip(edges[:-1], edges[1:]):
        keep = (strain > low) & (strain <= high)
        if keep.any():
            rows.append([0.5 * (low + high)] + [float(values[keep].mean()) for values in columns.values()])
    return list(columns), rows


def smoothed_peak(h):
    strain = -h["strain_11"]
    ratio = h["stress_ratio"]
    best = (0.0, 0.0)
    for s in strain[strain > SMOOTH]:
        mean = ratio[np.abs(strain - s) <= 0.5 * SMOOTH].mean()
        best = max(best, (float(mean), float(s)))
    return best


def main(stem, runs):
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.6))
    with open(f"{stem}.csv", "w") as csv:
        csv.write("run,strain_bin_centre,stress_ratio,q_over_p,volumetric_strain,void_ratio,coordination\n")
        for label, folder in runs:
            h = read_history(f"{folder}/history.h5")
            strain = -h["strain_11"]
            peak, at = smoothed_peak(h)
            axes[0].plot(100 * strain, h["stress_ratio"], lw=0.8, label=f"{label} (peak {peak:.3f} at {100 * at:.1f}%)")
            axes[1].plot(100 * strain, 100 * h["volumetric_strain"], lw=1, label=label)
            _, rows = binned(h)
            for row in rows:
                csv.write(f"{label}," + ",".join(f"{x:.5g}" for x in row) + "\n")
            print(f"{label}: smoothed peak {peak:.3f} at {100 * at:.1f}%, eps_v at 5/20/60%: "
                  + " ".join(f"{100 * np.interp(x, strain, h['volumetric_strain']):.2f}%" for x in (0.05, 0.2, 0.6)))
    axes[0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[1].set_ylabel(r"volumetric strain $\varepsilon_v$ (%), dilation positive")
    for ax in axes:
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{stem}.png", dpi=110)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], [tuple(arg.rsplit("=", 1)) for arg in sys.argv[2:]])
