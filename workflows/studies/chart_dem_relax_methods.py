#!/usr/bin/python3
"""Steps to a verified static state: damped relaxation against the FIRE minimiser
(docs/charts/dem_relax_methods_<LABELS>.png, .csv; docs/methods/dem.md, "Static states").

Each prepared assembly (LABEL=PATH) is loaded the way the paper configs loaded before the
quasi-static mode (OVAL's increments: 1e-4 of strain, each relaxed to an unbalanced-force ratio of
1e-2, checkpoints unrelaxed) to the largest of STRAINS, writing a checkpoint at each. Every
checkpoint is then relaxed by `aniso-dem relax` four ways: FIRE relaxing to a hundredth of the
tolerances before its 20,000-step verification (the default since 2026-12-08) and to a tenth (the
default before), damped (global damping 0.1) relaxing to half of them (the default before FIRE),
and damped relaxing to a tenth. The relaxed (sigma11 - sigma33)/p, void ratio and Z without
rattlers come from `aniso-fabric series`. Finished runs in WORK are reused; JOBS run side by side.

usage: chart_dem_relax_methods.py BUILD_DIR WORK OUTPUT STRAINS JOBS LABEL=PREPARED.h5...
       (STRAINS: comma-separated, e.g. 0.001,0.005,0.01,0.02,0.05,0.1,0.2,0.3)
"""
import concurrent.futures
import csv
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from runner import main_guarded, run_cached, settings_arguments, stage  # noqa: E402

METHODS = [("FIRE, margin 0.01", "fire_m0.01", ["dem.equilibrium.method=fire", "dem.equilibrium.margin=0.01"]),
           ("FIRE, margin 0.1", "fire_m0.1", ["dem.equilibrium.method=fire", "dem.equilibrium.margin=0.1"]),
           ("damped, margin 0.5", "damped_m0.5", ["dem.equilibrium.method=damped", "dem.equilibrium.margin=0.5"]),
           ("damped, margin 0.1", "damped_m0.1", ["dem.equilibrium.method=damped", "dem.equilibrium.margin=0.1"])]
LOADING = ["dem.load.increment=1e-4", "dem.load.increment_tolerance=1e-2", "dem.load.quasi_static=false",
           "dem.equilibrium.at_checkpoints=false"]
MAX_STEPS = 1_000_000
SUMMARY = re.compile(r"relax of .*: (\d+) steps \((\d+) verifying, (\d+) windows left\)")


def load(build, prepared, folder, strains):
    """The checkpoints load_000.h5 ... of the loading, in STRAINS' order (cached)."""
    names = [f"{folder}/load_{k:03d}.h5" for k in range(len(strains))]
    if all(os.path.exists(n) for n in names):
        return names
    os.makedirs(folder, exist_ok=True)
    settings = LOADING + [f"dem.output_dir={folder}", f"dem.load.final_strain={max(strains)}",
                          f"dem.load.checkpoint_strains=[{', '.join(str(s) for s in strains)}]",
                          f"dem.load.history_interval={max(strains) / 200}"]
    run_cached([stage(build, "dem"), "load", "--input", prepared, "--overwrite", *settings_arguments(settings)],
               folder, outputs=names)
    return names


def relax(build, checkpoint, folder, settings):
    """(steps, verifying steps, windows left, wall seconds, exit code) of one relaxation (cached)."""
    name = os.path.basename(checkpoint)
    log = f"{os.path.splitext(name)[0]}.log"
    # exit 5: no verified state within MAX_STEPS, a result of the study
    run = run_cached([stage(build, "dem"), "relax", "--input", checkpoint, "--output", f"{folder}/{name}",
                      *settings_arguments([f"dem.equilibrium.max_steps={MAX_STEPS}", *settings])],
                     folder, log=log, accept=(0, 5))
    match = SUMMARY.search(open(os.path.join(folder, log)).read())
    if match is None:
        return MAX_STEPS, 0, -1, run.wall, run.code
    return int(match[1]), int(match[2]), int(match[3]), run.wall, run.code


def fabric(build, files, out_dir):
    """Rows of `aniso-fabric series` by checkpoint file name."""
    present = [f for f in files if os.path.exists(f)]
    series = f"{out_dir}/fabric_series.h5"
    if os.path.exists(series):
        os.remove(series)  # redone each time: the relaxations present may have grown
    run_cached([stage(build, "fabric"), "series", "--input", *present, "--output", series], out_dir,
               outputs=[series])
    with open(f"{out_dir}/fabric_series.csv") as f:
        return {os.path.basename(row["source"]): row for row in csv.DictReader(f)}


def ratio13(row):
    return (float(row["stress_33"]) - float(row["stress_11"])) / float(row["p"])


def main(build, work, out, strains, jobs, assemblies):
    # RELAX_METHODS=fire_m0.01,fire_m0.1,damped_m0.5 runs a subset (the costly ovoids).
    chosen = os.environ.get("RELAX_METHODS")
    methods = [m for m in METHODS if chosen is None or m[1] in chosen.split(",")]
    rows = []
    for label, prepared in assemblies:
        checkpoints = load(build, prepared, f"{work}/{label}/loaded", strains)
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            tasks = {(key, c): pool.submit(relax, build, c, f"{work}/{label}/{key}", settings)
                     for _, key, settings in methods for c in checkpoints}
        loaded = fabric(build, checkpoints, f"{work}/{label}/loaded/fabric")
        for title, key, _ in methods:
            relaxed = fabric(build, [f"{work}/{label}/{key}/{os.path.basename(c)}" for c in checkpoints],
                             f"{work}/{label}/{key}/fabric")
            for strain, c in zip(strains, checkpoints):
                steps, verifying, windows, wall, code = tasks[(key, c)].result()
                name = os.path.basename(c)
                a, b = loaded[name], relaxed.get(name)
                rows.append({
                    "assembly": label, "strain": strain, "method": title, "steps": steps,
                    "verifying_steps": verifying, "windows_left": windows, "wall_s": f"{wall:.1f}",
                    "verified": int(code == 0), "ratio13_loaded": f"{ratio13(a):.4f}",
                    "ratio13_relaxed": f"{ratio13(b):.4f}" if b else "",
                    "void_ratio_loaded": f"{float(a['void_ratio']):.5f}",
                    "void_ratio_relaxed": f"{float(b['void_ratio']):.5f}" if b else "",
                    "z_loaded": f"{float(a['coordination_no_rattlers']):.3f}",
                    "z_relaxed": f"{float(b['coordination_no_rattlers']):.3f}" if b else ""})
    labels = [label for label, _ in assemblies]
    stem = f"{out}/dem_relax_methods_{'_'.join(labels)}"
    with open(f"{stem}.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    fig, axes = plt.subplots(1, len(labels), figsize=(6 * len(labels), 4.5), squeeze=False)
    for ax, label in zip(axes[0], labels):
        for title, _, _ in methods:
            mine = [r for r in rows if r["assembly"] == label and r["method"] == title]
            ax.plot([100 * r["strain"] for r in mine], [r["steps"] for r in mine], "o-", label=title)
            failed = [r for r in mine if not r["verified"]]
            ax.plot([100 * r["strain"] for r in failed], [r["steps"] for r in failed], "kx", ms=10)
        ax.axhline(20000, color="grey", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ of the checkpoint (%)")
        ax.set_ylabel("time steps to a verified static state")
        ax.set_title(f"{label}: relaxing loaded checkpoints (x: not verified)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{stem}.png", dpi=110)
    for r in rows:
        print(r)


if __name__ == "__main__":
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], [float(s) for s in sys.argv[4].split(",")],
                 int(sys.argv[5]), [a.split("=", 1) for a in sys.argv[6:]])
