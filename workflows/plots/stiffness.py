#!/usr/bin/python3
"""The stiffness figure family (Kuhn, Sun & Wang 2015, section 4: Figs. C123 and A) from the probes'
results (docs/formats/probe.md), against the loading strain -eps11.

  stiffness.py run PROBE_FOLDER OUTPUT.png
      one campaign run: every probe_<stem>.h5 in the folder, sorted by strain: C11/K_C, C22/K_C, C33/K_C
      (Fig. C123), (C11 - C33)/K_C and (C22 - C33)/K_C (Fig. A), K_C and max |D|; the numbers go to a
      CSV beside the figure and to the output
  stiffness.py shapes OUTPUT_PREFIX LABEL=PROBE_CSV_FOLDER,FABRIC_SERIES.csv[,MAX_STRAIN] [...]
      several shapes from the probes' CSVs and the fabric series: OUTPUT_PREFIX_C123.png (Fig. C123, a row
      per shape, the first 1% as a panel beside the full range) and OUTPUT_PREFIX_A.png (Fig. A, all
      shapes, with small-strain panels); prints Markdown tables of the Pearson correlations c1, c2 of
      C11 - C33 and C22 - C33 with each contact fabric (paper: H^c best, 0.985 / 0.981 averaged over four
      shapes), the ratio of (C11 - C33)/K_C to (H^c_11 - H^c_33)/(tr H^c / 3) (paper: about 4.1 at every
      strain) and the large-strain (C11 - C33)/K_C (paper: 1.4 - 2.1). MAX_STRAIN (a fraction) keeps only
      the checkpoints up to that strain. Probes whose checks failed (checks_passed = 0, or in a folder
      probes_unchecked beside PROBE_CSV_FOLDER) are drawn as open markers and left out of every number.
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cli import dispatch, output_and_labelled  # noqa: E402
from readers import read_fabric_series, read_probe, stem  # noqa: E402


# --- one run: the campaign's figure -------------------------------------------------------------------

def run_figure(arguments):
    if len(arguments) != 2:
        sys.exit(__doc__)
    folder, output = arguments
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


# --- several shapes: the paper's figures and numbers ------------------------------------------

# Column names of fabric_series.csv and the paper's symbols (as Markdown text).
FABRICS = [("H", "H^c"), ("F", "F^c"), ("G", "G^c"), ("H_strong", "H^c-strong"), ("F_strong", "F^c-strong"),
           ("G_strong", "G^c-strong")]
MIN_POINTS = 3  # fewer checked probes give no correlation or ratio (a shape whose probes were all refused)
SMALL_STRAIN = 0.0101  # the small-strain panels' range of -eps11 (1%, the checkpoint lies a hair above)


def read_probes(folder, passed=True):
    """{checkpoint stem: (strain, K_C, C 3x3)} from probe_<stem>.csv files: those whose checks passed,
    or with passed=False those a campaign kept with checks_passed = 0 (probe.check_increment = false)."""
    probes = {}
    for path in glob.glob(os.path.join(folder, "probe_*.csv")):
        probe = read_probe(path)
        if (probe["checks_passed"] != 0) == passed:
            probes[stem(probe["source"])] = (float(probe["strain"]), float(probe["K_C"]), probe["C"])
    return probes


def read_fabric(path):
    """{checkpoint stem: {column: value}} from a fabric_series.csv."""
    columns = read_fabric_series(path)
    if columns is None:  # a header without rows
        return {}
    numeric = [k for k, v in columns.items() if k != "source" and not isinstance(v, list)]
    return {stem(source): {k: float(columns[k][i]) for k in numeric} for i, source in enumerate(columns["source"])}


def unchecked_probes(probe_folder, max_strain="inf"):
    """(strain, K_C, C) arrays of the probes whose checks failed: kept in the folder with checks_passed = 0,
    or in the sibling folder probes_unchecked (refused, run again with the check off): drawn as open
    markers, left out of every number."""
    folder = os.path.join(os.path.dirname(os.path.normpath(probe_folder)), "probes_unchecked")
    found = {**read_probes(folder), **read_probes(probe_folder, passed=False)}
    probes = sorted((p for p in found.values() if p[0] <= float(max_strain)), key=lambda p: p[0])
    return (np.array([p[0] for p in probes]), np.array([p[1] for p in probes]),
            np.array([p[2] for p in probes]).reshape(-1, 3, 3))


def shape_series(probe_folder, fabric_csv, max_strain="inf"):
    probes, fabric = read_probes(probe_folder), read_fabric(fabric_csv)
    stems = sorted((s for s in probes if s in fabric and probes[s][0] <= float(max_strain)), key=lambda s: probes[s][0])
    strain = np.array([probes[s][0] for s in stems])
    K = np.array([probes[s][1] for s in stems])
    C = np.array([probes[s][2] for s in stems]).reshape(-1, 3, 3)
    return stems, strain, K, C, [fabric[s] for s in stems]


def anisotropy(rows, name, a, b):
    return np.array([r[f"{name}_{a}{a}"] - r[f"{name}_{b}{b}"] for r in rows])


def normalized_anisotropy(rows, name):
    trace = np.array([r[f"{name}_11"] + r[f"{name}_22"] + r[f"{name}_33"] for r in rows])
    return anisotropy(rows, name, 1, 3) / (trace / 3)


def small_strain_panel(axis):
    """The paper's insets, drawn as a panel beside the full range so that they hide no curve."""
    axis.set_xlim(0, 100 * SMALL_STRAIN)
    axis.set_xlabel(r"strain $-\varepsilon_{11}$ (%), first 1%")
    axis.grid(alpha=0.3)


def draw(full, small, x, y, **style):
    """Draws y(x) on the full range and on the small-strain panel; returns the line's colour."""
    (line,) = full.plot(100 * x, y, **style)
    keep = x <= SMALL_STRAIN
    small.plot(100 * x[keep], y[keep], **{**style, "color": line.get_color()})
    return line.get_color()


def draw_unchecked(full, small, x, y, color, label=None):
    """Probes the linearity check refused: open markers, no line."""
    if len(x):
        draw(full, small, x, y, ls="none", marker="o", ms=6, mfc="none", color=color, label=label)


def shape_figures(arguments):
    prefix, runs = output_and_labelled(arguments, __doc__)
    if any("," not in spec for _, spec in runs):
        sys.exit(__doc__)
    shapes = [(label, *shape_series(*spec.split(","))) for label, spec in runs]
    unchecked = [unchecked_probes(*[v for k, v in enumerate(spec.split(",")) if k != 1]) for _, spec in runs]
    for (label, spec), (_, _, strain, *_), (xu, *_) in zip(runs, shapes, unchecked):
        if len(strain) == 0 and len(xu) == 0:
            probe_folder, fabric_csv, *limit = spec.split(",")
            sys.exit(f"stiffness.py shapes: {label}: no probe in {probe_folder} (or probes_unchecked beside it) "
                     f"matches a checkpoint of {fabric_csv}" + (f" at a strain up to {limit[0]}" if limit else ""))
    # Fig. C123: one row per shape, the full range and the first 1% side by side.
    figure, axes = plt.subplots(len(shapes), 2, figsize=(10, 3.6 * len(shapes)), squeeze=False,
                                gridspec_kw={"width_ratios": [2, 1]})
    for (full, small), (label, _, strain, K, C, _), (xu, Ku, Cu) in zip(axes, shapes, unchecked):
        for i in range(3):
            color = draw(full, small, strain, C[:, i, i] / K, marker="o", ms=3, label=f"$C_{{{i + 1}{i + 1}}}/K_C$")
            draw_unchecked(full, small, xu, Cu[:, i, i] / Ku if len(xu) else xu, color,
                           "refused by the linearity check" if i == 2 else None)
        full.set_xlabel(r"strain $-\varepsilon_{11}$ (%)")
        full.set_ylabel(r"$C_{ii}/K_{\mathbf{C}}$")
        full.grid(alpha=0.3)
        full.legend(fontsize=8)
        small_strain_panel(small)
        full.set_title(f"Fig. C123 at paper size: {label}")
    figure.tight_layout()
    figure.savefig(f"{prefix}_C123.png", dpi=150)

    figure, axes = plt.subplots(2, 2, figsize=(11, 8), gridspec_kw={"width_ratios": [2, 1]})
    for row, (a, title) in enumerate([(1, r"(a) across $x_1$-$x_3$"), (2, r"(b) across $x_2$-$x_3$")]):
        full, small = axes[row]
        for k, ((label, _, x, Kx, Cx, _), (xu, Ku, Cu)) in enumerate(zip(shapes, unchecked)):
            # a subset's line must not hide its superset's
            color = draw(full, small, x, (Cx[:, a - 1, a - 1] - Cx[:, 2, 2]) / Kx, marker="o", ms=max(5 - k, 2),
                         lw=max(2.5 - 0.5 * k, 0.8), ls=["-", "--", ":", "-."][k % 4], label=label)
            draw_unchecked(full, small, xu, (Cu[:, a - 1, a - 1] - Cu[:, 2, 2]) / Ku if len(xu) else xu, color)
        full.set_xlabel(r"strain $-\varepsilon_{11}$ (%)")
        full.set_ylabel(fr"$(C_{{{a}{a}}} - C_{{33}})/K_{{\mathbf{{C}}}}$")
        full.set_title(f"Fig. A{title}")
        full.grid(alpha=0.3)
        full.legend(fontsize=8)
        small_strain_panel(small)
    figure.tight_layout()
    figure.savefig(f"{prefix}_A.png", dpi=150)

    print("| fabric | paper (four-shape mean) | " + " | ".join(f"{label} c1 / c2" for label, *_ in shapes) + " |")
    print("|" + " --- |" * (2 + len(shapes)))
    for name, symbol in FABRICS:
        cells = []
        for _, _, x, Kx, Cx, rows in shapes:
            if len(x) < MIN_POINTS:
                cells.append(f"n/a ({len(x)} checked probes)")
                continue
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
        if len(x) < MIN_POINTS:
            print(f"| {label} | {len(x)} | n/a | n/a | n/a |")
            continue
        a13 = (Cx[:, 0, 0] - Cx[:, 2, 2]) / Kx
        ratio = a13 / normalized_anisotropy(rows, "H")
        late = x >= 0.01
        peak = int(np.argmax(a13))
        late_ratio = (f"{np.median(ratio[late]):.2f} ({ratio[late].min():.2f} - {ratio[late].max():.2f})"
                      if late.any() else "n/a (no probe from 1%)")
        print(f"| {label} | {len(x)} | {a13[-1]:.2f} at {100 * x[-1]:.0f}% | {a13[peak]:.2f} ({100 * x[peak]:.2g}%) "
              f"| {late_ratio} |")


if __name__ == "__main__":
    dispatch({"run": run_figure, "shapes": shape_figures}, __doc__, sys.argv[1:])
