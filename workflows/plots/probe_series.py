#!/usr/bin/python3
"""Directional stiffness against loading strain (the paper's Figs. C123 and A).

Reads every probe_<stem>.h5 in a folder (one per checkpoint of a loading run), sorts them by
the checkpoint's loading strain and charts C11/K_C, C22/K_C, C33/K_C, (C11 - C33)/K_C,
(C22 - C33)/K_C and K_C against strain.
The numbers go to a CSV beside the figure.

usage: probe_series.py PROBE_FOLDER OUTPUT.png
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from probe_io import read_probe  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    folder, output = sys.argv[1:]
    paths = [p for p in glob.glob(os.path.join(folder, "probe_*.h5")) if "_fork" not in os.path.basename(p)]
    if not paths:
        sys.exit(f"no probe_*.h5 results in {folder}")
    results = sorted((read_probe(p) for p in paths), key=lambda r: r["strain"])
    strain = np.array([r["strain"] for r in results])
    K = np.array([r["K_C"] for r in results])
    C = np.array([np.diag(r["C"]) for r in results])
    D = np.array([np.abs(r["D"]).max() for r in results])
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(15, 4.2))
    x = np.maximum(strain, 1e-6)
    for i in range(3):
        left.semilogx(x, C[:, i] / K, "o-", label=f"$C_{{{i + 1}{i + 1}}}/K_C$")
    left.set_xlabel(r"loading strain $-\varepsilon_{11}$ (isotropic start plotted at 1e-6)")
    left.set_ylabel("$C_{ii}/K_C$")
    left.legend()
    left.grid(alpha=0.3)
    # Paper Fig. A: the stiffness deviator across x1-x3 and x2-x3, normalized by K_C.
    middle.semilogx(x, (C[:, 0] - C[:, 2]) / K, "o-", label="$(C_{11}-C_{33})/K_C$")
    middle.semilogx(x, (C[:, 1] - C[:, 2]) / K, "s--", label="$(C_{22}-C_{33})/K_C$")
    middle.axhline(0, color="0.5", lw=0.8)
    middle.set_xlabel(r"loading strain $-\varepsilon_{11}$")
    middle.set_title("stiffness anisotropy (paper Fig. A)", fontsize=9)
    middle.legend()
    middle.grid(alpha=0.3)
    left.set_title("directional stiffness (paper Fig. C123)", fontsize=9)
    right.semilogx(x, K / 1e6, "ko-", label="$K_C$")
    right.semilogx(x, D / 1e6, "s--", color="C3", label=r"max $|D_{ij}|$")
    right.set_xlabel(r"loading strain $-\varepsilon_{11}$")
    right.set_ylabel("MPa")
    right.legend()
    right.grid(alpha=0.3)
    # No folder in the title: figures must be identical for identical results wherever they run.
    fig.suptitle("incremental stiffness C from the oedometric probes", fontsize=10)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    csv = os.path.splitext(output)[0] + ".csv"
    with open(csv, "w") as f:
        f.write("strain,K_C,C11/K_C,C22/K_C,C33/K_C,(C11-C33)/K_C,(C22-C33)/K_C,max|D|/K_C,checks_passed,source\n")
        for r, s, k, c, d in zip(results, strain, K, C, D):
            f.write(f"{s:.6g},{k:.6g},{c[0] / k:.4f},{c[1] / k:.4f},{c[2] / k:.4f},{(c[0] - c[2]) / k:.4f},"
                    f"{(c[1] - c[2]) / k:.4f},{d / k:.4f},{int(r['checks_passed'])},{r['source']}\n")
    print(open(csv).read(), end="")


if __name__ == "__main__":
    main()
