#!/usr/bin/python3
"""The preparation study (workflows/studies/preparation_study.py; docs/methods/dem.md, "The preparation
study"): how the way an assembly of the paper's void ratio was made sets its loading.

Reads WORK/<variant>/ (variant.txt: the config and its settings; prepare/prepared.h5; load/history.h5;
failed.txt where prepare missed the target band) and writes
  OUTPUT/dem_preparation_study.csv         per variant: the consolidated e, Z and Z without rattlers
                                           (the history's first row), the peak of (sigma11 - sigma33)/p
                                           and its strain, the ratio at 20%, eps_v at 5, 10 and 20% and
                                           its minimum, wall times
  OUTPUT/dem_preparation_study_curves.csv  every variant on one strain grid (0.25% bins)
  OUTPUT/dem_preparation_study.png         a row of curves per shape, then peak strain, peak and eps_v
                                           at the last strain against Z without rattlers

usage: chart_preparation_study.py WORK OUTPUT
       chart_preparation_study.py --from-curves OUTPUT
"""
import csv
import glob
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from chart_dem_dempla import GRID_STEP, names_in, on_grid, read_curves, write_curves  # noqa: E402
from runner import read_record  # noqa: E402
from readers import read_history  # noqa: E402

NAME = "dem_preparation_study"
SHAPE_MARKERS = {"spheres": "o", "ovoids-0.8": "s", "ovoids-0.625": "^", "ovoids-0.5": "D"}


def shape_of(config):
    """'workflows/configs/paper-ovoids-0.625.toml' -> 'ovoids-0.625'."""
    return os.path.basename(config).removesuffix(".toml").removeprefix("paper-")


def describe(settings):
    """'--set dem.material.friction_prepare=0' lines -> 'friction_prepare=0, ...' ('paper config')."""
    pairs = [f"{key.split('.')[-1]}={value}" for key, value in
             (s.split("=", 1) for s in settings if s != "--set")]
    return ", ".join(pairs) if pairs else "the paper config"


def read_variants(work):
    variants, runs = [], {}
    for path in sorted(glob.glob(f"{work}/*/variant.txt")):
        folder = os.path.dirname(path)
        name = os.path.basename(folder)
        lines = open(path).read().split("\n")
        config, settings = lines[0], [s for s in lines[1:] if s]
        row = {"variant": name, "shape": shape_of(config), "settings": describe(settings)}
        prepare, load = read_record(f"{folder}/prepare", "prepare.log"), read_record(f"{folder}/load", "load.log")
        row["prepare_s"] = f"{prepare['wall_seconds']:.0f}" if prepare else ""
        row["load_s"] = f"{load['wall_seconds']:.0f}" if load else ""
        history = f"{folder}/load/history.h5"
        if prepare and prepare["code"] != 0:
            row["outcome"] = f"prepare missed the target band (exit {prepare['code']})"
        elif load is None:
            row["outcome"] = "not loaded yet"
        else:
            row["outcome"] = "loaded"
            h = read_history(history)
            s = -np.column_stack([h["stress_11"], h["stress_22"], h["stress_33"]])
            p = s.mean(axis=1)
            runs[name] = {"strain": -h["strain_11"], "q13": (s[:, 0] - s[:, 2]) / p, "q23": (s[:, 1] - s[:, 2]) / p,
                          "eps_v": h["volumetric_strain"], "coordination": h["coordination"]}
            row.update(e0=f"{h['void_ratio'][0]:.4f}", Z0=f"{h['coordination'][0]:.3f}",
                       Z0_no_rattlers=f"{h['coordination_no_rattlers'][0]:.3f}")
        variants.append(row)
    if not runs:
        raise SystemExit(f"chart_preparation_study.py: no loaded variant in {work}")
    return variants, runs


def add_outcomes(variants, grid):
    """The peak of (sigma11 - sigma33)/p and its strain, the ratio and eps_v at the last strain, eps_v
    at 5 and 10%, and the largest contraction, from the binned curves."""
    strain = grid["strain"]
    for row in variants:
        name = row["variant"]
        if f"{name}:q13" not in grid:
            continue
        q13, eps_v = grid[f"{name}:q13"], grid[f"{name}:eps_v"]
        last = int(np.flatnonzero(~np.isnan(q13))[-1])
        k = int(np.nanargmax(q13))
        row.update(peak_q13=f"{q13[k]:.3f}", peak_strain=f"{strain[k]:.4f}", final_strain=f"{strain[last]:.4f}",
                   q13_final=f"{q13[last]:.3f}", eps_v_final=f"{eps_v[last]:.4f}",
                   eps_v_min=f"{np.nanmin(eps_v):.4f}")
        for s in (0.05, 0.10):
            j = int(np.argmin(abs(strain - (s - 0.5 * GRID_STEP))))
            row[f"eps_v_{100 * s:g}pc"] = f"{eps_v[j]:.4f}" if strain[last] >= s - GRID_STEP else ""


def write_summary(variants, path):
    keys = ["variant", "shape", "settings", "outcome", "e0", "Z0", "Z0_no_rattlers", "peak_q13", "peak_strain",
            "final_strain", "q13_final", "eps_v_5pc", "eps_v_10pc", "eps_v_final", "eps_v_min", "prepare_s", "load_s"]
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=keys, extrasaction="ignore")
        writer.writeheader()
        for row in variants:
            writer.writerow({k: row.get(k, "") for k in keys})
    for row in variants:
        print({k: row.get(k, "") for k in keys})


def read_summary(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def chart(variants, grid, path):
    loaded = [r for r in variants if r.get("peak_q13")]
    shapes = sorted({r["shape"] for r in loaded}, key=lambda s: list(SHAPE_MARKERS).index(s)
                    if s in SHAPE_MARKERS else 99)
    strain = 100 * grid["strain"]
    fig, axes = plt.subplots(len(shapes) + 1, 3, figsize=(14, 3.6 * (len(shapes) + 1)), squeeze=False)
    # One colour per way of preparing (its seeds share it), so that a way's scatter reads as such.
    # (a frictionless-made way's first stop is only where its corrections start).
    way = {r["variant"]: ", ".join(p.split("=")[0] if p.startswith("compaction_stop") else p
                                   for p in r["settings"].split(", ") if not p.startswith("seed=")) or
           "the paper config" for r in loaded}
    ways = list(dict.fromkeys(way.values()))
    colours = {name: f"C{ways.index(w) % 10}" for name, w in way.items()}
    for row_axes, shape in zip(axes, shapes):
        for ax, (q, title) in zip(row_axes, [("q13", "(sigma11 - sigma33)/p"), ("eps_v", "eps_v [%] (dilation +)"),
                                             ("coordination", "Z (all particles)")]):
            for r in loaded:
                if r["shape"] != shape:
                    continue
                values = grid[f"{r['variant']}:{q}"] * (100 if q == "eps_v" else 1)
                ax.plot(strain, values, color=colours[r["variant"]],
                        label=f"{r['settings']} (Z* {float(r['Z0_no_rattlers']):.2f})")
            ax.set_title(f"{shape}: {title}", fontsize=10)
            ax.grid(alpha=0.3)
            ax.set_xlabel("compressive strain -eps11 [%]")
        row_axes[2].legend(fontsize=6, loc="lower right")  # Z rises within 2% and stays: room below
    for ax, (key, title, scale) in zip(axes[-1], [("peak_strain", "strain at the peak [%]", 100),
                                                  ("peak_q13", "peak (sigma11 - sigma33)/p", 1),
                                                  ("eps_v_final", "eps_v at the last strain [%]", 100)]):
        for r in loaded:
            # Hollow: an assembly away from the paper's e (the density control).
            hollow = abs(float(r["e0"]) - 0.556) > 0.01
            ax.plot(float(r["Z0_no_rattlers"]), scale * float(r[key]), SHAPE_MARKERS.get(r["shape"], "x"),
                    color=colours[r["variant"]], ms=8, mfc="none" if hollow else colours[r["variant"]])
        for shape in shapes:
            ax.plot([], [], SHAPE_MARKERS.get(shape, "x"), color="k", label=shape)
        ax.set_xlabel("Z without rattlers after consolidation")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
    axes[-1][0].legend(fontsize=8)
    fig.suptitle("The preparation as a lever: assemblies near e = 0.556 made in different ways, "
                 "loaded alike (oval behaviour, 1000 particles; hollow: e = 0.53)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv):
    if len(argv) == 3 and argv[1] == "--from-curves":
        out = argv[2]
        chart(read_summary(f"{out}/{NAME}.csv"), read_curves(f"{out}/{NAME}_curves.csv"), f"{out}/{NAME}.png")
        return
    if len(argv) != 3:
        raise SystemExit(__doc__)
    work, out = argv[1], argv[2]
    os.makedirs(out, exist_ok=True)
    variants, runs = read_variants(work)
    grid = on_grid(runs)
    assert set(names_in(grid)) == set(runs)
    add_outcomes(variants, grid)
    write_curves(grid, f"{out}/{NAME}_curves.csv")
    write_summary(variants, f"{out}/{NAME}.csv")
    chart(variants, grid, f"{out}/{NAME}.png")


if __name__ == "__main__":
    main(sys.argv)
