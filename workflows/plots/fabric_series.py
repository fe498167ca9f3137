#!/usr/bin/python3
"""The paper's fabric figures from `aniso-fabric series` results (fabric_series.h5):
fabric_anisotropy.png: (A11 - A33)/(tr A/3) against -eps11 for J^p (Fig. 4), I^s, S^s (Fig. 5),
F^c, H^c, H^c-strong (Fig. 6a-c) and W3 normalized (Fig. 11); (A22 - A33)/(tr A/3) of
H^c-strong (Fig. 6d); fabric_stress.png: H^c-strong_11 - _33 against (s11 - s33)/p (Fig. 7a) and
chi^v / N_p (both forms); fabric_correlations.csv: c1, c2 of each measure (Table 2).

usage: fabric_series.py FABRIC_SERIES.h5 OUTPUT_FOLDER
"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("J", "Fig. 4"), ("I", "Fig. 5a"), ("S", "Fig. 5b"), ("F", "Fig. 6a"), ("H", "Fig. 6b"),
          ("H_strong", "Fig. 6c"), ("W320_normalized", "Fig. 11")]


def main(path, folder):
    with h5py.File(path) as f:
        s = {name: d[()] for name, d in f["series"].items()}
        correlations = {name: dict(g.attrs) for name, g in f["correlations"].items()}
    strain = -100 * s["strain_11"]
    fig, axes = plt.subplots(2, 4, figsize=(15, 7))
    for ax, (name, figure) in zip(axes.flat, PANELS):
        ax.plot(strain, s[f"{name}_anisotropy_13"], marker="o", ms=3)
        ax.set_title(f"{name}: (A11 - A33)/(tr A/3), paper {figure}", fontsize=9)
    ax = axes.flat[len(PANELS)]
    ax.plot(strain, s["H_strong_anisotropy_23"], marker="o", ms=3)
    ax.set_title("H_strong: (A22 - A33)/(tr A/3), paper Fig. 6d", fontsize=9)
    for ax in axes.flat:
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{folder}/fabric_anisotropy.png", dpi=110)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    ratio = (-s["stress_11"] + s["stress_33"]) / s["p"]
    axes[0].plot(s["H_strong_11"] - s["H_strong_33"], ratio, marker="o", ms=3)
    axes[0].set_xlabel(r"$H^{c-strong}_{11} - H^{c-strong}_{33}$")
    axes[0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[0].set_title("paper Fig. 7a", fontsize=9)
    axes[1].plot(strain, s["chi_paper_per_particle"], label=r"$1 + N_p - N_c$ (paper, eq. Chis1)")
    axes[1].plot(strain, s["chi_torus_per_particle"], label=r"$N_p - N_c + N_3 - N_4$ (periodic cell)")
    axes[1].set_xlabel(r"$-\varepsilon_{11}$ (%)")
    axes[1].set_ylabel(r"$\chi^v / N_p$")
    axes[1].legend(fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{folder}/fabric_stress.png", dpi=110)

    with open(f"{folder}/fabric_correlations.csv", "w") as out:
        out.write("measure,c1,c2,n_points\n")
        for name, a in sorted(correlations.items()):
            out.write(f"{name},{a['c1']:.4f},{a['c2']:.4f},{a['n_points']}\n")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
