#!/usr/bin/python3
"""The campaign report: key numbers and the figures, one line of reading each,
with the paper's trends beside the run's.

Reads the run folder (dem/history.h5) and the CSV files the figure scripts wrote
into RUN_FOLDER/figures (stress_strain, fabric_correlations, stiffness, voids,
permeability); a stage whose figure is missing is reported as not run.

usage: report.py RUN_FOLDER > report.md
"""
import csv
import os
import sys

import numpy as np

from fabric import PAPER
from readers import read_history

# Paper Table 2: c1, c2 of six contact tensors against the stress, all shapes, 0-60% strain.
PAPER_TABLE_2 = {name: (c1, c2) for name, c1, c2 in PAPER}
PAPER_NAMES = {"H_strong": "H c-strong", "F_strong": "F c-strong", "G_strong": "G c-strong", "H": "H c",
               "F": "F c", "G": "G c"}


def read_csv(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows or None


def column(rows, name):
    return np.array([float(r[name]) for r in rows])


def print_table(header, rows):
    """A Markdown table: the header, the separator, then one line per row of cell strings."""
    print("| " + " | ".join(header) + " |")
    print("|" + " --- |" * len(header))
    for row in rows:
        print("| " + " | ".join(row) + " |")


def percent(row):
    return f"{100 * float(row['strain']):.3g}%"


def trend(values, tolerance):
    change = values[-1] - values[0]
    return "rises" if change > tolerance else "falls" if change < -tolerance else "stays level"


def dem_section(folder, h):
    strain = -h["strain_11"]
    p = h["p"]
    ratio = (-h["stress_11"] + h["stress_33"]) / p
    peak = int(np.argmax(ratio))
    steady = strain > min(0.002, strain[-1] / 2)
    servo = np.abs(h["servo_error"][steady]) if steady.any() else np.abs(h["servo_error"])
    print("## DEM: biaxial plane strain at constant mean stress\n")
    print_table(["quantity", "value"], [
        ["void ratio at the start of loading", f"{h['void_ratio'][0]:.4f} (paper: 0.556)"],
        ["coordination number at start (without rattlers)",
         f"{h['coordination'][0]:.3f} ({h['coordination_no_rattlers'][0]:.3f})"],
        ["peak stress ratio (s11 - s33)/p", f"{ratio[peak]:.4f} at -eps11 = {100 * strain[peak]:.3g}%"],
        ["final strain", f"{100 * strain[-1]:.3g}%"],
        ["final void ratio", f"{h['void_ratio'][-1]:.4f}"],
        ["mean-stress servo error after the first 0.2% strain: median, max",
         f"{100 * np.median(servo):.3f}%, {100 * servo.max():.3f}%"],
        ["inertial number (median)", f"{np.median(h['inertial_number']):.3g}"]])
    print()
    print("![stress-strain](figures/stress_strain.png)\n")
    volumetric = h["volumetric_strain"]
    softening = ratio[-1] < 0.95 * ratio[peak]
    contraction = volumetric.min() < 0 and int(np.argmin(volumetric)) < len(volumetric) - 1
    dilates = volumetric[-1] > volumetric.min()
    print("Reading: the stress ratio " + ("peaks and then softens" if softening else "has not passed its peak")
          + f" by {100 * strain[-1]:.3g}% strain; the volume "
          + ("contracts first and then dilates" if contraction and dilates else
             "only dilates" if not contraction else "only contracts")
          + ". The paper's dense assemblies (its Fig. 3) peak and soften and dilate strongly beyond about 5% "
          "strain; an assembly looser than the paper's e = 0.556 contracts more and peaks less. "
          "The numbers behind the figure are in figures/stress_strain.csv.\n")
    return ratio[peak]


def fabric_section(folder):
    rows = read_csv(os.path.join(folder, "figures", "fabric_correlations.csv"))
    print("## Fabric: contact, particle and void tensors (paper Figs. 4-7, 11; Table 2)\n")
    if rows is None:
        print("Not run (no fabric results).\n")
        return None
    print("![fabric anisotropies](figures/fabric_anisotropy.png)\n")
    print("![fabric and stress](figures/fabric_stress.png)\n")
    by_name = {r["measure"].removesuffix("_vs_stress"): r for r in rows if r["measure"].endswith("_vs_stress")}
    ranked = sorted((n for n in PAPER_TABLE_2 if n in by_name),
                    key=lambda n: -(float(by_name[n]["c1"]) + float(by_name[n]["c2"])))
    paper_ranked = sorted(PAPER_TABLE_2, key=lambda n: -sum(PAPER_TABLE_2[n]))
    print("Table 2: Pearson correlations of the deviatoric contact tensors with the deviatoric stress "
          "(eqs. (c1), (c2)), ranked by c1 + c2.\n")
    print_table(["rank", "tensor", "c1", "c2", "paper rank", "paper c1", "paper c2"],
                [[str(k), PAPER_NAMES[name], f"{float(by_name[name]['c1']):.3f}",
                  f"{float(by_name[name]['c2']):.3f}", str(paper_ranked.index(name) + 1),
                  f"{PAPER_TABLE_2[name][0]:.3f}", f"{PAPER_TABLE_2[name][1]:.3f}"]
                 for k, name in enumerate(ranked, 1)])
    n_points = by_name[ranked[0]]["n_points"] if ranked else "0"
    best = PAPER_NAMES[ranked[0]] if ranked else "none"
    print(f"\nReading: over {n_points} checkpoints, {best} correlates best with the stress; in the paper "
          "H c-strong does (0.993, 0.988), and the strong-contact tensors rank above those of all contacts. "
          "The numbers are in figures/fabric_correlations.csv and fabric/fabric_series.csv.\n")
    return [PAPER_NAMES[n] for n in ranked]


def probe_section(folder):
    rows = read_csv(os.path.join(folder, "figures", "stiffness.csv"))
    print("## Incremental stiffness from oedometric probes (paper Figs. C123 and A)\n")
    if rows is None:
        print("Not run (no probe results).\n")
        return None
    rows.sort(key=lambda r: float(r["strain"]))
    strain = column(rows, "strain")
    c11, c33, kc = column(rows, "C11/K_C"), column(rows, "C33/K_C"), column(rows, "K_C")
    print("![stiffness](figures/stiffness.png)\n")
    print_table(["-eps11", "K_C (MPa)", "C11/K_C", "C22/K_C", "C33/K_C", "(C11 - C33)/K_C", "checks passed"],
                [[percent(r), f"{float(r['K_C']) / 1e6:.1f}"]
                 + [f"{float(r[name]):.3f}" for name in ("C11/K_C", "C22/K_C", "C33/K_C", "(C11-C33)/K_C")]
                 + ["yes" if r["checks_passed"] == "1" else "no"] for r in rows])
    print(f"\nReading: from {100 * strain[0]:.3g}% to {100 * strain[-1]:.3g}% strain C11/K_C {trend(c11, 0.05)} "
          f"({c11[0]:.2f} to {c11[-1]:.2f}) and C33/K_C {trend(c33, 0.05)} ({c33[0]:.2f} to {c33[-1]:.2f}); "
          f"K_C goes from {kc[0] / 1e6:.0f} to {kc[-1] / 1e6:.0f} MPa. The paper's spheres (Fig. C123) show C11 "
          "rising and C33 falling with a stiffness network that is altered but not degraded.\n")
    return c11


def voids_section(folder):
    rows = read_csv(os.path.join(folder, "figures", "voids.csv"))
    print("## Void morphology from voxel images (paper Figs. VoidDistrib, Lambda_vs_strain, R_vs_strain)\n")
    if rows is None:
        print("Not run (no voxel results).\n")
        return
    rows.sort(key=lambda r: float(r["strain"]))
    L13 = column(rows, "L_v_11") - column(rows, "L_v_33")
    R13 = column(rows, "R_v_11") - column(rows, "R_v_33")
    print("![voids](figures/voids.png)\n")
    print_table(["-eps11", "porosity", "median void size / D50", "L11 - L33", "L22 - L33", "R11 - R33",
                 "R22 - R33"],
                [[percent(r), f"{float(r['porosity']):.4f}", f"{float(r['void_size_median_d50']):.3f}"]
                 + [f"{float(r[f'{m}_v_{i}']) - float(r[f'{m}_v_33']):+.4f}" for m in "LR" for i in ("11", "22")]
                 for r in rows])
    print(f"\nReading: L11 - L33 goes from {L13[0]:+.3f} to {L13[-1]:+.3f} and R11 - R33 from {R13[0]:+.3f} to "
          f"{R13[-1]:+.3f}: the voids grow " + ("longer along" if L13[-1] > L13[0] else "shorter along")
          + " the compression direction x1. In the paper, sphere voids grow longer along x1 "
          "(L11 - L33 > 0) while the flat ovoids' voids lie across it.\n")


def permeability_section(folder):
    rows = read_csv(os.path.join(folder, "figures", "permeability.csv"))
    print("## Permeability from lattice Boltzmann flow (paper Fig. K_vs_strain)\n")
    if rows is None:
        print("Not run (no permeability results).\n")
        return None
    rows.sort(key=lambda r: float(r["strain"]))
    print("![permeability](figures/permeability.png)\n")
    print_table(["-eps11", "K11 (um^2)", "K22 (um^2)", "K33 (um^2)", "(K11 - K33)/tr K", "(K22 - K33)/tr K"],
                [[percent(r)] + [f"{float(r[f'K{i}_m2']) * 1e12:.3f}" for i in ("11", "22", "33")]
                 + [f"{float(r[name]):+.4f}" for name in ("(K11-K33)/trK", "(K22-K33)/trK")] for r in rows])
    k13 = column(rows, "(K11-K33)/trK")
    early = k13[1] if len(k13) > 1 else k13[0]
    print(f"\nReading: (K11 - K33)/tr K goes from {k13[0]:+.4f} to {k13[-1]:+.4f} ({early:+.4f} at the second "
          "checkpoint with flow). The paper finds it negative early in the loading for spheres and alpha = 0.8 and "
          "positive for the flatter ovoids: a sphere run with a positive early value differs from the paper there "
          "(a looser packing, a smaller cell and a coarser image than the paper's are the candidates).\n")
    return k13


def main(folder):
    h = read_history(os.path.join(folder, "dem", "history.h5"))
    print("# aniso campaign report\n")
    print(f"Run folder: `{os.path.abspath(folder)}`\n")  # the make campaign passes it relative to workflows/
    peak = dem_section(folder, h)
    ranking = fabric_section(folder)
    c11 = probe_section(folder)
    voids_section(folder)
    k13 = permeability_section(folder)
    print("## Key numbers\n")
    print(f"- peak stress ratio (s11 - s33)/p: {peak:.3f}")
    if c11 is not None:
        print(f"- C11/K_C: {c11[0]:.2f} at the start, {c11[-1]:.2f} at the last probed checkpoint")
    if k13 is not None:
        print(f"- (K11 - K33)/tr K: {k13[0]:+.4f} at the start, {k13[-1]:+.4f} at the last checkpoint with flow")
    if ranking:
        print(f"- Table 2 ranking: {', '.join(ranking)} (paper: {', '.join(PAPER_NAMES.values())})")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
