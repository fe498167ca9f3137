#!/usr/bin/python3
"""The paper's void and permeability figures (Kuhn, Sun & Wang 2015, sections 3.4 and 5) for several
particle shapes, from the CSVs paper_voids_csv.py writes per shape (docs/paper-size/<shape>/):

  PREFIX_distributions.png  Fig. VoidDistrib: (a) the pore-size distribution f_rho (eq. (fr)) at the
                            first (0%) and last (60%) checkpoint, (b) the directed free-path
                            distributions f_l1, f_l3 (eq. (fli)) and (c) the radial-breadth
                            distributions f_r1, f_r3 (eq. (fri)) at the last checkpoint
  PREFIX_anisotropy.png     Figs. Lambda_vs_strain and LLambda_vs_strain: L^v_11 - L^v_33, L^v_22 - L^v_33
                            (eq. (Lambdaii)) and the same for R^v (eq. (Rii))
  PREFIX_permeability.png   Fig. K_vs_strain: (K11 - K33)/tr K and (K22 - K33)/tr K, for the shapes
                            with a permeability.csv

Sizes are in units of D50, strain is -eps11 in per cent. The script prints the numbers the comparison
quotes.

usage: paper_voids.py PREFIX LABEL=FOLDER [LABEL=FOLDER ...]
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

STRAIN_LABEL = r"strain $-\varepsilon_{11}$ [%]"


def read_columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    columns = {key: np.array([float(r[key]) for r in rows]) for key in rows[0] if key != "checkpoint"}
    columns["checkpoint"] = [r["checkpoint"] for r in rows]
    columns["strain"] = -100 * columns["strain_11"]
    return columns


def read_curves(path):
    """{(checkpoint, distribution): (sizes, fractions)} with the checkpoint's strain in per cent."""
    curves, strains = {}, {}
    with open(path) as f:
        for r in csv.DictReader(f):
            key = (r["checkpoint"], r["distribution"])
            curves.setdefault(key, ([], []))
            curves[key][0].append(float(r["size_d50"]))
            curves[key][1].append(float(r["fraction"]))
            strains[r["checkpoint"]] = -100 * float(r["strain_11"])
    return {k: (np.array(s), np.array(v)) for k, (s, v) in curves.items()}, strains


def read_shape(folder):
    shape = {"voids": read_columns(os.path.join(folder, "voids.csv"))}
    shape["curves"], shape["curve_strains"] = read_curves(os.path.join(folder, "void_curves.csv"))
    flow = os.path.join(folder, "permeability.csv")
    shape["flow"] = read_columns(flow) if os.path.exists(flow) else None
    return shape


def plot_distributions(prefix, shapes):
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for n, (label, shape) in enumerate(shapes):
        color = f"C{n}"
        strains = shape["curve_strains"]
        first, last = min(strains, key=strains.get), max(strains, key=strains.get)
        for stem, style in ((first, "--"), (last, "-")):
            sizes, fraction = shape["curves"][(stem, "ball")]
            axes[0].plot(sizes, fraction, style, color=color, lw=1,
                         label=f"{label}, {shape['curve_strains'][stem]:.0f}%")
        for panel, kind in ((1, "spar"), (2, "disk")):
            for axis, style in (("1", "-"), ("3", ":")):
                sizes, fraction = shape["curves"][(last, f"{kind}_x{axis}")]
                axes[panel].plot(sizes, fraction, style, color=color, lw=1, label=f"{label}, $x_{axis}$")
    axes[0].set_title(r"(a) pore size $f^v_\rho$, 0% (dashed) and 60%", fontsize=9)
    axes[0].set_xlabel(r"ball radius $\rho / D_{50}$")
    axes[1].set_title(r"(b) directed free paths $f^v_{\ell_1}$, $f^v_{\ell_3}$ at 60%", fontsize=9)
    axes[1].set_xlabel(r"spar length $\ell_i / D_{50}$")
    axes[1].set_xlim(0, 3)
    axes[2].set_title(r"(c) directed radial breadths $f^v_{r_1}$, $f^v_{r_3}$ at 60%", fontsize=9)
    axes[2].set_xlabel(r"disk radius $r_i / D_{50}$")
    for ax in axes:
        ax.set_ylabel("fraction of the void volume kept")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(f"{prefix}_distributions.png", dpi=150)


def plot_strain_panels(path, shapes, panels, ylabel):
    """One panel per (title, key, function of the shape's columns); every shape on each."""
    rows = (len(panels) + 1) // 2
    fig, axes = plt.subplots(rows, 2, figsize=(10, 4 * rows), squeeze=False)
    for ax, (title, key, value) in zip(axes.flat, panels):
        for n, (label, shape) in enumerate(shapes):
            if shape[key] is None:
                continue
            ax.plot(shape[key]["strain"], value(shape[key]), "o-", ms=2.5, lw=0.8, color=f"C{n}", label=label)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel(STRAIN_LABEL)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=150)


def difference(name, a, b):
    return lambda columns: columns[f"{name}_{a}{a}"] - columns[f"{name}_{b}{b}"]


def print_numbers(shapes):
    for label, shape in shapes:
        v = shape["voids"]
        last = -1
        print(f"{label}: porosity {v['porosity'][0]:.4f} -> {v['porosity'][last]:.4f}; "
              f"median void size {v['void_size_median_d50'][0]:.4f} -> {v['void_size_median_d50'][last]:.4f} D50; "
              f"at {v['strain'][last]:.0f}%: L11-L33 {v['L_v_11'][last] - v['L_v_33'][last]:+.3f}, "
              f"L22-L33 {v['L_v_22'][last] - v['L_v_33'][last]:+.3f}, R11-R33 {v['R_v_11'][last] - v['R_v_33'][last]:+.3f}, "
              f"R22-R33 {v['R_v_22'][last] - v['R_v_33'][last]:+.3f}; free paths l1, l3 "
              f"{v['free_path_median_1_d50'][last]:.3f}, {v['free_path_median_3_d50'][last]:.3f} D50")
        if shape["flow"] is not None:
            f = shape["flow"]
            for k in range(len(f["strain"])):
                print(f"  K at {f['strain'][k]:.3g}%: (K11-K33)/trK {f['K11_minus_K33_over_trace'][k]:+.4f}, "
                      f"(K22-K33)/trK {f['K22_minus_K33_over_trace'][k]:+.4f}, K11 {f['K_11'][k]:.3e} m^2")


def print_correlations(shapes):
    """Pearson correlation of the permeability anisotropy with those of L^v and R^v (the paper's section
    5: negative with L^v, positive with R^v, across 1-3 and 2-3), per shape and pooled, over the
    checkpoints with a permeability result."""
    pooled = {}
    for label, shape in shapes:
        if shape["flow"] is None:
            continue
        v, f = shape["voids"], shape["flow"]
        rows = [v["checkpoint"].index(stem) for stem in f["checkpoint"]]
        for pair, (a, b) in (("13", (1, 3)), ("23", (2, 3))):
            k = f[f"K{a}{a}_minus_K33_over_trace"]
            for name in ("L_v", "R_v"):
                void = (v[f"{name}_{a}{a}"] - v[f"{name}_{b}{b}"])[rows]
                pooled.setdefault((pair, name), ([], []))
                pooled[(pair, name)][0].extend(k)
                pooled[(pair, name)][1].extend(void)
                if len(k) > 2:
                    print(f"  {label}: Pearson of K {pair} with {name} {pair}: {np.corrcoef(k, void)[0, 1]:+.3f} "
                          f"({len(k)} checkpoints)")
    for (pair, name), (k, void) in pooled.items():
        if len(k) > 2:
            print(f"pooled: Pearson of K {pair} with {name} {pair}: {np.corrcoef(k, void)[0, 1]:+.3f} ({len(k)} points)")


def main():
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    prefix = sys.argv[1]
    shapes = [(label, read_shape(folder)) for label, folder in (a.rsplit("=", 1) for a in sys.argv[2:])]
    plot_distributions(prefix, shapes)
    plot_strain_panels(f"{prefix}_anisotropy.png", shapes, [
        (r"$\overline{L}^v_{11} - \overline{L}^v_{33}$ (median free path)", "voids", difference("L_v", 1, 3)),
        (r"$\overline{L}^v_{22} - \overline{L}^v_{33}$", "voids", difference("L_v", 2, 3)),
        (r"$\overline{R}^v_{11} - \overline{R}^v_{33}$ (median radial breadth)", "voids", difference("R_v", 1, 3)),
        (r"$\overline{R}^v_{22} - \overline{R}^v_{33}$", "voids", difference("R_v", 2, 3))], "anisotropy")
    if any(shape["flow"] is not None for _, shape in shapes):
        plot_strain_panels(f"{prefix}_permeability.png", shapes, [
            (r"(a) $(K_{11} - K_{33}) / \mathrm{tr}\,\mathbf{K}$", "flow", lambda c: c["K11_minus_K33_over_trace"]),
            (r"(b) $(K_{22} - K_{33}) / \mathrm{tr}\,\mathbf{K}$", "flow", lambda c: c["K22_minus_K33_over_trace"])],
            "permeability anisotropy")
    print_numbers(shapes)
    print_correlations(shapes)


if __name__ == "__main__":
    main()
