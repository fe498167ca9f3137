#!/usr/bin/python3
"""The paper's section 4 at paper size, from committed CSVs: Fig. C123 (C11, C22, C33 over K_C
against strain, with a small-strain inset), Fig. A (the stiffness anisotropies (C11 - C33)/K_C
and (C22 - C33)/K_C of every shape given, with insets), and the numbers the text states: the
Pearson correlations c1, c2 of C11 - C33 and C22 - C33 with each contact fabric (paper: H^c best,
0.985 / 0.981 averaged over four shapes), the ratio of (C11 - C33)/K_C to the fabric anisotropy
(H^c_11 - H^c_33)/(tr H^c / 3) (paper: about 4.1 at every strain) and the large-strain
(C11 - C33)/K_C (paper: 1.4 - 2.1). Prints Markdown tables (docs/paper-comparison.md).

usage: paper_stiffness.py OUTPUT_PREFIX LABEL=PROBE_CSV_FOLDER,FABRIC_SERIES.csv[,MAX_STRAIN] [...]
  writes OUTPUT_PREFIX_C123.png (first shape) and OUTPUT_PREFIX_A.png (all shapes); MAX_STRAIN
  (a fraction) keeps only the checkpoints up to that loading strain
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Column names of fabric_series.csv and the paper's symbols (as Markdown text).
FABRICS = [("H", "H^c"), ("F", "F^c"), ("G", "G^c"), ("H_strong", "H^c-strong"), ("F_strong", "F^c-strong"),
           ("G_strong", "G^c-strong")]
SMALL_STRAIN = 0.0101  # the insets' range of -eps11 (1%, the checkpoint lies a hair above)


def stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def read_probes(folder):
    """{checkpoint stem: (strain, K_C, C 3x3)} from probe_<stem>.csv files."""
    probes = {}
    for path in glob.glob(os.path.join(folder, "probe_*.csv")):
        with open(path) as f:
            row = next(csv.DictReader(f))
        C = np.array([[float(row[f"C_{i}{j}"]) for j in (1, 2, 3)] for i in (1, 2, 3)])
        probes[stem(row["source"])] = (float(row["strain"]), float(row["K_C"]), C)
    return probes


def read_fabric(path):
    """{checkpoint stem: {column: value}} from a fabric_series.csv."""
    with open(path) as f:
        return {stem(row["source"]): {k: float(v) for k, v in row.items() if k != "source"}
                for row in csv.DictReader(f)}


def shape_series(probe_folder, fabric_csv, max_strain="inf"):
    probes, fabric = read_probes(probe_folder), read_fabric(fabric_csv)
    stems = sorted((s for s in probes if s in fabric and probes[s][0] <= float(max_strain)), key=lambda s: probes[s][0])
    strain = np.array([probes[s][0] for s in stems])
    K = np.array([probes[s][1] for s in stems])
    C = np.array([probes[s][2] for s in stems])
    return stems, strain, K, C, [fabric[s] for s in stems]


def anisotropy(rows, name, a, b):
    return np.array([r[f"{name}_{a}{a}"] - r[f"{name}_{b}{b}"] for r in rows])


def normalized_anisotropy(rows, name):
    trace = np.array([r[f"{name}_11"] + r[f"{name}_22"] + r[f"{name}_33"] for r in rows])
    return anisotropy(rows, name, 1, 3) / (trace / 3)


def percent(x):
    return 100 * np.maximum(x, 1e-5)


def with_inset(axis, x, series, ylabel):
    """series: [(y, style kwargs)] drawn on `axis` and on a small-strain inset."""
    inset = axis.inset_axes([0.52, 0.1, 0.44, 0.4])
    for y, style in series:
        axis.plot(100 * x, y, **style)
        small = x <= SMALL_STRAIN
        inset.plot(100 * x[small], y[small], **{k: v for k, v in style.items() if k != "label"})
    axis.set_xlabel(r"strain $-\varepsilon_{11}$ (%)")
    axis.set_ylabel(ylabel)
    inset.set_xlim(0, 100 * SMALL_STRAIN)
    inset.tick_params(labelsize=7)
    inset.set_title(r"$-\varepsilon_{11} \leq 1\%$", fontsize=7)
    axis.grid(alpha=0.3)


def main(prefix, runs):
    shapes = [(label, *shape_series(*spec.split(","))) for label, spec in runs]
    label, _, strain, K, C, _ = shapes[0]
    figure, axis = plt.subplots(figsize=(6, 4.5))
    with_inset(axis, strain, [(C[:, i, i] / K, {"marker": "o", "ms": 3, "label": f"$C_{{{i + 1}{i + 1}}}/K_C$"})
                              for i in range(3)], r"$C_{ii}/K_{\mathbf{C}}$")
    axis.set_title(f"Fig. C123 at paper size: {label}")
    axis.legend(loc="upper left", fontsize=8)
    figure.tight_layout()
    figure.savefig(f"{prefix}_C123.png", dpi=150)

    figure, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for k, (a, title) in enumerate([(1, r"(a) across $x_1$-$x_3$"), (2, r"(b) across $x_2$-$x_3$")]):
        with_inset(axes[k], strain, [], "")
        for label, _, x, Kx, Cx, _ in shapes:
            axes[k].plot(100 * x, (Cx[:, a - 1, a - 1] - Cx[:, 2, 2]) / Kx, "o-", ms=3, label=label)
        axes[k].set_ylabel(fr"$(C_{{{a}{a}}} - C_{{33}})/K_{{\mathbf{{C}}}}$")
        axes[k].set_title(f"Fig. A{title}")
        axes[k].legend(fontsize=8, loc="upper left")
    for ax in axes:  # the insets were drawn empty above; fill them now with every shape
        inset = ax.child_axes[0]
        a = 1 if ax is axes[0] else 2
        for label, _, x, Kx, Cx, _ in shapes:
            small = x <= SMALL_STRAIN
            inset.plot(100 * x[small], ((Cx[:, a - 1, a - 1] - Cx[:, 2, 2]) / Kx)[small], "o-", ms=2)
    figure.tight_layout()
    figure.savefig(f"{prefix}_A.png", dpi=150)

    print("| fabric | paper (four-shape mean) | " + " | ".join(f"{label} c1 / c2" for label, *_ in shapes) + " |")
    print("|" + " --- |" * (2 + len(shapes)))
    for name, symbol in FABRICS:
        cells = []
        for _, _, x, Kx, Cx, rows in shapes:
            c1 = np.corrcoef(Cx[:, 0, 0] - Cx[:, 2, 2], anisotropy(rows, name, 1, 3))[0, 1]
            c2 = np.corrcoef(Cx[:, 1, 1] - Cx[:, 2, 2], anisotropy(rows, name, 2, 3))[0, 1]
            cells.append(f"{c1:.3f} / {c2:.3f}")
        paper = "0.985 / 0.981 (best)" if name == "H" else ""
        print(f"| {symbol} | {paper} | " + " | ".join(cells) + " |")
    print()
    print("| shape | checkpoints | (C11 - C33)/K_C at the largest strain | max (C11 - C33)/K_C (strain) "
          "| ratio to (H11 - H33)/(tr H/3), median (range, strains >= 1%) |")
    print("| --- | --- | --- | --- | --- |")
    for label, _, x, Kx, Cx, rows in shapes:
        a13 = (Cx[:, 0, 0] - Cx[:, 2, 2]) / Kx
        ratio = a13 / normalized_anisotropy(rows, "H")
        late = x >= 0.01
        peak = int(np.argmax(a13))
        print(f"| {label} | {len(x)} | {a13[-1]:.2f} at {100 * x[-1]:.0f}% | {a13[peak]:.2f} ({100 * x[peak]:.2g}%) "
              f"| {np.median(ratio[late]):.2f} ({ratio[late].min():.2f} - {ratio[late].max():.2f}) |")


if __name__ == "__main__":
    if len(sys.argv) < 3 or any("=" not in arg or "," not in arg for arg in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], [tuple(arg.split("=", 1)) for arg in sys.argv[2:]])
