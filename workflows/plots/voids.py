#!/usr/bin/python3
"""The void and permeability figure family (Kuhn, Sun & Wang 2015, sections 3.4 and 5) from the voxel
stage's voids_<stem>.h5 and the LBM's permeability_<stem>.h5 (docs/formats/voids.md, permeability.md).
Sizes are in units of D50, strain is -eps11 in per cent.

  voids.py run RUN_FOLDER OUTPUT_FOLDER
      one campaign run, its strains from the fabric series (fabric/fabric_series.h5, matched by each
      result's source_hash): voids.png with (a) the void-size distribution f_rho (ball opening, eq. (fr)),
      (b) the directed free paths f_l_i (spar, eq. (fli)), (c) the radial breadths f_r_i (disk, eq. (fri))
      at the first and last checkpoint, (d) L^v and (e) R^v anisotropies (eqs. (Lambdaii), (Rii)) and the
      porosity against strain; permeability.png (paper Fig. K_vs_strain) with (K11 - K33)/tr K,
      (K22 - K33)/tr K and the diagonal of K; voids.csv and permeability.csv beside them
  voids.py csv RUN_FOLDER OUTPUT_FOLDER
      the paper figures' input from one run folder, its strains from the checkpoints dem/load_NNN.h5:
      voids.csv (one row per checkpoint: strain, porosity, the median void size, free paths l_i and
      radial breadths r_i in d50, the diagonals of L^v and R^v), void_curves.csv (f_rho, f_l_i, f_r_i at
      the first and last checkpoint) and permeability.csv (K [m^2], its anisotropies, per direction the
      steps, the Reynolds number and the narrowest throat [voxel]) where the LBM ran
  voids.py shapes PREFIX LABEL=FOLDER [LABEL=FOLDER ...]
      several shapes from the CSVs `voids.py csv` wrote (docs/paper-size/<shape>/):
      PREFIX_distributions.png (Fig. VoidDistrib: f_rho at the first and last checkpoint, f_l1, f_l3 and
      f_r1, f_r3 at the last), PREFIX_anisotropy.png (Figs. Lambda_vs_strain, LLambda_vs_strain) and
      PREFIX_permeability.png (Fig. K_vs_strain, for the shapes with a permeability.csv); prints the
      numbers the comparison quotes and the correlations of K's anisotropy with L^v's and R^v's
"""
import csv
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cli import dispatch, output_and_labelled  # noqa: E402
from readers import (AXES, VOID_CURVES, checkpoint_strain, is_collected_permeability, read_fabric_series,  # noqa: E402
                     read_permeability, read_table, read_voids)

AXIS_NAMES = ("1", "2", "3")


# --- one run: the campaign's figures -------------------------------------------------------------



def strain_by_hash(folder):
    """checkpoint content hash -> -eps11, from the fabric series of the run."""
    path = os.path.join(folder, "fabric", "fabric_series.h5")
    if not os.path.exists(path):
        sys.exit(f"voids.py run: {path} is missing: the strains come from the fabric series")
    return read_fabric_series(path)["source_hash"]


def strain_of(path, result, strains):
    if result["source_hash"] not in strains:
        sys.exit(f"voids.py run: {path} comes from a checkpoint (hash {result['source_hash']}) "
                 "that the fabric series does not hold")
    return strains[result["source_hash"]]


def draw_voids(folder, output, strains):
    paths = sorted(glob.glob(os.path.join(folder, "voxel", "voids_*.h5")))
    if not paths:
        return None
    results = sorted(((strain_of(p, r, strains), r) for p, r in ((p, read_voids(p)) for p in paths)),
                     key=lambda r: r[0])
    strain = np.array([s for s, _ in results])
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    ends = [results[0], results[-1]] if len(results) > 1 else [results[0]]
    for (s, r), style in zip(ends, ["-", "--"]):
        label = f"{100 * s:.3g}%"
        sizes, fraction = r["curves"]["ball"]
        axes[0, 0].plot(sizes, fraction, style, color="k", label=label)
        for a, color in zip(AXIS_NAMES, ["C0", "C1", "C2"]):
            sizes, fraction = r["curves"][f"spar_x{a}"]
            axes[0, 1].plot(sizes, fraction, style, color=color, label=f"$x_{a}$, {label}")
            sizes, fraction = r["curves"][f"disk_x{a}"]
            axes[0, 2].plot(sizes, fraction, style, color=color, label=f"axis $x_{a}$, {label}")
    titles = [r"(a) void size $f_\rho$ (ball opening)", r"(b) free path $f_{\ell_i}$ (spar along $x_i$)",
              r"(c) radial breadth $f_{r_i}$ (disk, axis $x_i$)"]
    for ax, title in zip(axes[0], titles):
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("size / D50")
        ax.set_ylabel("fraction of the void kept")
        ax.legend(fontsize=7)
    axes[0, 1].set_xlim(0, 3)
    L = np.array([r["L_v"] for _, r in results])
    R = np.array([r["R_v"] for _, r in results])
    for ax, tensor, name in [(axes[1, 0], L, "L^v"), (axes[1, 1], R, "R^v")]:
        ax.plot(100 * strain, tensor[:, 0] - tensor[:, 2], "o-", label=f"${name}_{{11}} - {name}_{{33}}$")
        ax.plot(100 * strain, tensor[:, 1] - tensor[:, 2], "s--", label=f"${name}_{{22}} - {name}_{{33}}$")
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=8)
    axes[1, 0].set_title("(d) median free-path anisotropy, eq. (Lambdaii)", fontsize=9)
    axes[1, 1].set_title("(e) median radial-breadth anisotropy, eq. (Rii)", fontsize=9)
    porosity = np.array([r["porosity"] for _, r in results])
    axes[1, 2].plot(100 * strain, porosity, "ko-")
    axes[1, 2].set_title("porosity of the image", fontsize=9)
    axes[1, 2].set_xlabel(r"$-\varepsilon_{11}$ (%)")
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    with open(os.path.splitext(output)[0] + ".csv", "w") as out:
        out.write("strain,porosity,void_size_median_d50," + ",".join(f"free_path_median_{a}_d50" for a in AXIS_NAMES) + ","
                  + ",".join(f"breadth_median_{a}_d50" for a in AXIS_NAMES) + ","
                  + ",".join(f"L_v_{a}{a}" for a in AXIS_NAMES) + "," + ",".join(f"R_v_{a}{a}" for a in AXIS_NAMES) + "\n")
        for s, r in results:
            values = [s, r["porosity"], r["void_size_median"] / r["d50"], *(r["free_path_median"] / r["d50"]),
                      *(r["breadth_median"] / r["d50"]), *r["L_v"], *r["R_v"]]
            out.write(",".join(f"{v:.6g}" for v in values) + "\n")
    return results


def draw_permeability(folder, output, strains):
    paths = [p for p in sorted(glob.glob(os.path.join(folder, "lbm", "permeability_*.h5"))) if is_collected_permeability(p)]
    if not paths:
        return None
    results = []
    for path in paths:
        flow = read_permeability(path)
        results.append((strain_of(path, flow, strains), flow["K"], flow["symmetry_error"]))
    results.sort(key=lambda r: r[0])
    strain = 100 * np.array([s for s, _, _ in results])
    diagonal = np.array([np.diag(K) for _, K, _ in results])
    trace = diagonal.sum(axis=1)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.plot(strain, (diagonal[:, 0] - diagonal[:, 2]) / trace, "o-", label=r"$(K_{11}-K_{33})/\mathrm{tr}\,K$")
    left.plot(strain, (diagonal[:, 1] - diagonal[:, 2]) / trace, "s--", label=r"$(K_{22}-K_{33})/\mathrm{tr}\,K$")
    left.axhline(0, color="0.5", lw=0.8)
    left.set_title("induced permeability anisotropy (paper Fig. K_vs_strain)", fontsize=9)
    for a in range(3):
        right.plot(strain, diagonal[:, a] * 1e12, "o-", label=f"$K_{{{a + 1}{a + 1}}}$")
    right.set_ylabel(r"$\mu$m$^2$")
    right.set_title("diagonal of the permeability tensor", fontsize=9)
    for ax in (left, right):
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    with open(os.path.splitext(output)[0] + ".csv", "w") as out:
        out.write("strain,K11_m2,K22_m2,K33_m2,(K11-K33)/trK,(K22-K33)/trK,symmetry_error\n")
        for (s, K, symmetry), d, t in zip(results, diagonal, trace):
            out.write(f"{s:.6g},{d[0]:.6g},{d[1]:.6g},{d[2]:.6g},{(d[0] - d[2]) / t:.5f},{(d[1] - d[2]) / t:.5f},"
                      f"{symmetry:.3g}\n")
    return results


def run_figures(arguments):
    if len(arguments) != 2:
        sys.exit(__doc__)
    folder, figures = arguments
    strains = strain_by_hash(folder)
    os.makedirs(figures, exist_ok=True)
    draw_voids(folder, os.path.join(figures, "voids.png"), strains)
    draw_permeability(folder, os.path.join(figures, "permeability.png"), strains)


# --- the paper figures' CSVs of one run ---------------------------------------------------------

def checkpoint_strain_of(run, stem):
    """Engineering strain eps_11 of the run's checkpoint dem/<stem>.h5."""
    try:
        return checkpoint_strain(os.path.join(run, "dem", f"{stem}.h5"))
    except FileNotFoundError as missing:
        sys.exit(f"voids.py csv: {missing}")


def stem_of(path, prefix):
    return os.path.basename(path)[len(prefix):-len(".h5")]


def void_rows(run):
    rows, curves = [], {}
    for path in sorted(glob.glob(os.path.join(run, "voxel", "voids_load_*.h5"))):
        stem = stem_of(path, "voids_")
        v = read_voids(path)
        d50 = v["d50"]
        row = {"checkpoint": stem, "strain_11": checkpoint_strain_of(run, stem), "porosity": float(v["porosity"]),
               "void_size_median_d50": float(v["void_size_median"]) / d50}
        for name, key in (("free_path_median", "free_path_median_{a}_d50"), ("breadth_median", "breadth_median_{a}_d50")):
            for a in AXES:
                row[key.format(a=a)] = float(v[name][a - 1]) / d50
        for name in ("L_v", "R_v"):
            for a in AXES:
                row[f"{name}_{a}{a}"] = float(v[name][a - 1])
        curves[stem] = v["curves"]
        rows.append(row)
    return rows, curves


def permeability_rows(run, strains):
    rows = []
    # Only the collected results: the per-direction files of a job array lie beside them.
    for path in sorted(glob.glob(os.path.join(run, "lbm", "permeability_image_load_*.h5"))):
        stem = stem_of(path, "permeability_image_")
        if not re.fullmatch(r"load_\d+", stem):
            continue
        flow = read_permeability(path)
        K, runs = flow["K"], flow["runs"]
        row = {"checkpoint": stem, "strain_11": strains.get(stem, checkpoint_strain_of(run, stem)),
               "porosity": float(flow["porosity"]), "tau": float(flow["tau"])}
        for i in AXES:
            for j in AXES:
                row[f"K_{i}{j}"] = float(K[i - 1, j - 1])
        trace = float(np.trace(K))
        row["K11_minus_K33_over_trace"] = (K[0, 0] - K[2, 2]) / trace
        row["K22_minus_K33_over_trace"] = (K[1, 1] - K[2, 2]) / trace
        row["symmetry_error"] = float(flow["symmetry_error"])
        for r, axis in enumerate(runs["axis"]):
            row[f"steps_{axis}"] = int(runs["steps"][r])
            row[f"reynolds_{axis}"] = float(runs["reynolds"][r])
            row[f"throat_width_{axis}_voxels"] = float(runs["throat_width"][r])
        rows.append(row)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.9g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"wrote {path} ({len(rows)} rows)")


def csv_files(arguments):
    if len(arguments) != 2:
        sys.exit(__doc__)
    run, out = arguments
    rows, curves = void_rows(run)
    if not rows:
        sys.exit(f"voids.py csv: no {run}/voxel/voids_load_*.h5: run the campaign's voxel stage first")
    os.makedirs(out, exist_ok=True)
    write_csv(os.path.join(out, "voids.csv"), rows)
    strains = {r["checkpoint"]: r["strain_11"] for r in rows}
    curve_rows = []
    for stem in (rows[0]["checkpoint"], rows[-1]["checkpoint"]):
        for name in VOID_CURVES:
            sizes, fractions = curves[stem][name]
            curve_rows += [{"checkpoint": stem, "strain_11": strains[stem], "distribution": name,
                            "size_d50": float(s), "fraction": float(v)} for s, v in zip(sizes, fractions)]
    write_csv(os.path.join(out, "void_curves.csv"), curve_rows)
    flow = permeability_rows(run, strains)
    if flow:
        write_csv(os.path.join(out, "permeability.csv"), flow)


# --- several shapes: the paper's figures ------------------------------------------------------------

STRAIN_LABEL = r"strain $-\varepsilon_{11}$ [%]"


def read_columns(path):
    """A CSV of `voids.py csv` as columns, with the strain -eps11 in per cent."""
    columns = read_table(path)
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


def shape_figures(arguments):
    prefix, folders = output_and_labelled(arguments, __doc__)
    shapes = [(label, read_shape(folder)) for label, folder in folders]
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
    dispatch({"run": run_figures, "csv": csv_files, "shapes": shape_figures}, __doc__, sys.argv[1:])
