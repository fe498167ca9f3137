#!/usr/bin/python3
"""Paper Fig. 3 (a) and (c) for several particle shapes on one chart: (s11 - s33)/p and the
volumetric strain against -eps11, plus the void ratio and the mean particle-axis orientation
<a1 a1> (the share of the axes along the compression direction x1; 1/3 when isotropic).
Writes shapes_stress_strain.png and shapes_stress_strain.csv (the numbers behind the plot).

usage: shapes_stress_strain.py OUTPUT_PREFIX LABEL=HISTORY [LABEL=HISTORY ...]   (history.h5 or history.csv)
  e.g. shapes_stress_strain.py docs/charts/demo_shapes "alpha 1.0=runs/demo/dem/history.h5" ...
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402


def curves(h):
    strain = -h["strain_11"]
    return {"strain": strain, "stress ratio": (h["stress_33"] - h["stress_11"]) / h["p"],
            "volumetric strain": h["volumetric_strain"], "void ratio": h["void_ratio"],
            "axis orientation 11": h["axis_orientation_11"]}


def main(prefix, runs):
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    rows = []
    for label, path in runs:
        c = curves(read_history(path))
        peak = int(np.argmax(c["stress ratio"]))
        for ax, name in zip(axes.flat, ["stress ratio", "volumetric strain", "void ratio", "axis orientation 11"]):
            ax.plot(100 * c["strain"], c[name], label=label, lw=1)
        rows += [[label] + [f"{c[k][i]:.6g}" for k in c] for i in range(len(c["strain"]))]
        print(f"{label}: e0 = {c['void ratio'][0]:.4f}, peak (s11 - s33)/p = {c['stress ratio'][peak]:.3f} at "
              f"{100 * c['strain'][peak]:.3g}%, at {100 * c['strain'][-1]:.3g}%: ratio "
              f"{c['stress ratio'][-1]:.3f}, e = {c['void ratio'][-1]:.4f}, "
              f"<a1 a1> {c['axis orientation 11'][0]:.3f} -> {c['axis orientation 11'][-1]:.3f}")
    titles = ["(a) stress ratio (s11 - s33)/p", "(c) volumetric strain (compression < 0)", "void ratio e",
              "mean axis orientation <a1 a1> (1/3 isotropic)"]
    for ax, title in zip(axes.flat, titles):
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("-eps11 (%)")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}_stress_strain.png", dpi=120)
    with open(f"{prefix}_stress_strain.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["shape", "minus_strain_11", "stress_ratio_s11_s33_over_p", "volumetric_strain", "void_ratio",
                         "axis_orientation_11"])
        writer.writerows(rows)


if __name__ == "__main__":
    if len(sys.argv) < 3 or any("=" not in arg for arg in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], [tuple(arg.rsplit("=", 1)) for arg in sys.argv[2:]])
