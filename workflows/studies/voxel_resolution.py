#!/usr/bin/python3
"""Speed/accuracy chart of the voxel stage: medians of the ball, spar and disk distributions, L^v,
R^v and the porosity against the resolution (voxels per d50), next to the cost of the run, with
the finest resolution as the converged reference (the porosity also against the exact solid
volume of the spheres). Runs aniso-voxel once per resolution (results kept in WORK, reused when
present) and writes docs/charts/voxel_resolution.png and .csv.

usage: voxel_resolution.py CHECKPOINT.h5 [--bin BUILD_DIR] [--work DIR] [--out docs/charts]
                           [--resolutions 5,7.5,10,15,20,25,30,40] [--steps 1,0.5,0.25]

The radius step (voxel.radius_step) is the second knob: at the default resolution, radii k * step
are compared with every distinct digital element (step 0, the default).
"""
import argparse
import csv
import math
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from runner import main_guarded, run_cached, settings_arguments  # noqa: E402
from readers import read_voids  # noqa: E402


def run(binary, checkpoint, resolution, work, step=0.0):
    folder = os.path.join(work, f"res_{resolution:g}_step_{step:g}")
    stem = os.path.splitext(os.path.basename(checkpoint))[0]
    result = os.path.join(folder, f"voids_{stem}.h5")
    done = run_cached([binary, "--input", checkpoint,
                       *settings_arguments([f"voxel.output_dir='{folder}'", f"voxel.resolution={resolution}",
                                            "voxel.write_image=false", f"voxel.radius_step={step}",
                                            "voxel.threads=1"])], folder, outputs=[result])
    wall, cpu = done.wall, done.cpu
    v = read_voids(result)
    d50 = v["d50"]
    row = {"resolution": resolution, "radius_step": step, "wall_s": wall, "cpu_s": cpu, "voxels": v["voxels"],
           "porosity": float(v["porosity"]), "ball": float(v["void_size_median"]) / d50}
    for a in range(3):
        row[f"spar{a + 1}"] = float(v["free_path_median"][a]) / d50
        row[f"disk{a + 1}"] = float(v["breadth_median"][a]) / d50
        row[f"L{a + 1}"] = float(v["L_v"][a])
        row[f"R{a + 1}"] = float(v["R_v"][a])
    curves = {name: v["curves"][name] for name in ("ball", "disk_x1", "spar_x1")}
    return row, curves


def exact_porosity(checkpoint):
    with h5py.File(checkpoint, "r") as f:
        d = f["particles/diameter"][...]
        lengths = f["cell/lengths"][...]
    return 1 - np.sum(math.pi / 6 * d ** 3) / np.prod(lengths)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("checkpoint")
    parser.add_argument("--bin", default=os.path.join(os.path.dirname(__file__), "../../build"))
    parser.add_argument("--work", default="/tmp/aniso-voxel-resolution")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "../../docs/charts"))
    parser.add_argument("--resolutions", default="5,7.5,10,15,20,25,30,40")
    parser.add_argument("--steps", default="1,0.5,0.25")
    parser.add_argument("--default-resolution", type=float, default=20)
    args = parser.parse_args()
    binary = os.path.join(args.bin, "voxel/aniso-voxel")
    resolutions = [float(r) for r in args.resolutions.split(",")]
    rows, curves = [], {}
    for r in resolutions:
        row, c = run(binary, os.path.abspath(args.checkpoint), r, args.work)
        rows.append(row)
        curves[r] = c
    reference = rows[-1]
    porosity = exact_porosity(args.checkpoint)
    keys = ["ball"] + [f"spar{a}" for a in (1, 2, 3)] + [f"disk{a}" for a in (1, 2, 3)]
    for row in rows:
        row["max_median_error"] = max(abs(row[k] / reference[k] - 1) for k in keys)
        row["max_spar_error"] = max(abs(row[f"spar{a}"] / reference[f"spar{a}"] - 1) for a in (1, 2, 3))
        row["max_round_error"] = max(abs(row[k] / reference[k] - 1) for k in ("ball", "disk1", "disk2", "disk3"))
        row["max_LR_error"] = max(abs(row[f"{m}{a}"] - reference[f"{m}{a}"]) for m in "LR" for a in (1, 2, 3))
        row["porosity_error"] = abs(row["porosity"] - porosity)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "voxel_resolution.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    # The radius step at the default resolution against every distinct element (step 0).
    exact, _ = run(binary, os.path.abspath(args.checkpoint), args.default_resolution, args.work, 0.0)
    step_rows = []
    for step in [float(v) for v in args.steps.split(",")]:
        row, _ = run(binary, os.path.abspath(args.checkpoint), args.default_resolution, args.work, step)
        row["max_median_error"] = max(abs(row[k] / exact[k] - 1) for k in ("ball", "disk1", "disk2", "disk3"))
        step_rows.append(row)
    exact["max_median_error"] = 0.0
    step_rows.append(exact)
    with open(os.path.join(args.out, "voxel_radius_step.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(step_rows[0].keys()))
        writer.writeheader()
        writer.writerows(step_rows)

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    res = [row["resolution"] for row in rows]
    ax = axes[0, 0]
    for k, style in zip(keys, ["k-o", "r-s", "g-s", "b-s", "r--^", "g--^", "b--^"]):
        ax.plot(res, [row[k] for row in rows], style, label={"ball": "ball rho"}.get(k, k.replace("spar", "spar l").replace("disk", "disk r")))
    ax.set_xlabel("resolution [voxels per d50]")
    ax.set_ylabel("median [d50]")
    ax.set_title("medians of the distributions")
    ax.legend(fontsize=8, ncol=2)
    ax = axes[0, 1]
    cost = [row["cpu_s"] for row in rows[:-1]]
    ax.loglog(cost, [row["max_spar_error"] for row in rows[:-1]], "k-o", label="max rel. error, 3 spar medians")
    ax.loglog(cost, [row["max_round_error"] for row in rows[:-1]], "k--o", mfc="none",
              label="max rel. error, ball + 3 disk medians")
    ax.loglog(cost, [max(row["max_LR_error"], 1e-5) for row in rows[:-1]], "m-s", label="max abs. error of L^v, R^v")
    ax.loglog(cost, [max(row["porosity_error"], 1e-5) for row in rows[:-1]], "c-^", label="porosity error (exact)")
    for row in rows[:-1]:
        ax.annotate(f"{row['resolution']:g}", (row["cpu_s"], row["max_spar_error"]), fontsize=8,
                    textcoords="offset points", xytext=(4, 4))
    ax.loglog([r["cpu_s"] for r in step_rows[:-1]], [max(r["max_median_error"], 1e-5) for r in step_rows[:-1]],
              "y-D", label=f"radius step k*s vs every element, {args.default_resolution:g}/d50 (ball, disk medians)")
    for r in step_rows[:-1]:
        ax.annotate(f"s={r['radius_step']:g}", (r["cpu_s"], max(r["max_median_error"], 1e-5)), fontsize=8,
                    textcoords="offset points", xytext=(4, -10))
    ax.set_xlabel("cost: CPU seconds, one thread (digitize + all openings)")
    ax.set_ylabel(f"error against {reference['resolution']:g} voxels per d50")
    ax.set_title("cost vs error")
    ax.legend(fontsize=8)
    for ax, name, label in [(axes[1, 0], "ball", "ball radius rho"), (axes[1, 1], "spar_x1", "spar length l_1")]:
        for r in resolutions[::2] + ([resolutions[-1]] if len(resolutions) % 2 == 0 else []):
            size, f = curves[r][name]
            ax.plot(size, f, "-", label=f"{r:g} voxels/d50", drawstyle="default")
        ax.set_xlabel(f"{label} [d50]")
        ax.set_ylabel("f (fraction of void kept)")
        ax.set_xlim(0, 0.5 if name == "ball" else 3.0)
        ax.legend(fontsize=8)
        ax.set_title(f"f curve: {label}")
    fig.suptitle(f"aniso-voxel resolution study: {os.path.basename(args.checkpoint)} "
                 f"({rows[-1]['voxels']} voxels at {reference['resolution']:g}/d50)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "voxel_resolution.png"), dpi=110)
    for row in rows + step_rows:
        print(", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items()))


if __name__ == "__main__":
    main_guarded(main)
