#!/usr/bin/python3
"""Cost against the TRT relaxation time tau: docs/charts/lbm_tau.png.

For five images (a simple cubic sphere array at solid fraction 0.125 and 16 voxels per diameter,
random packings of spheres at porosity 0.4 with 10 and 6 voxels per diameter in 64^3 and 10 in 96^3,
and a dense random packing with throats of one to three voxels) and tau from 0.55 to 10, one
aniso-lbm run along x1 with the defaults (automatic force, tolerance 1e-5): the steps to convergence
(the cost, independent of the machine and of the rank count), the wall time, and the deviation of K11
from a tightly converged run. tau = 0 is the automatic choice (lbm/force_choice.hpp), drawn as a star.
Every run is a real aniso-lbm invocation; rows go to lbm_tau.csv, and runs already listed there are
reused (delete the csv to redo them).

usage: [RANKS=N] chart_lbm_tau.py BUILD_FOLDER WORK_FOLDER OUTPUT_FOLDER
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from runner import RunTable, main_guarded, run_cached, settings_arguments, stage  # noqa: E402
from readers import read_permeability  # noqa: E402

TAUS = [0.6, 0.8, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0]
DEFAULT_TOLERANCE = 1e-5
AUTOMATIC = 0.0
FIELDS = ["case", "tau", "tolerance", "steps", "seconds", "k11", "reynolds", "body_force", "chosen_tau", "ranks"]


def sphere_array_side(diameter, phi):
    return round(diameter / 2 / (3 * phi / (4 * math.pi)) ** (1 / 3))


# name -> (label, make_lbm_image arguments, taus, reference (tau, tolerance))
CASES = {
    "sphere_array": ("sphere array, phi = 0.125, 16 voxels per diameter, 26^3",
                     ["sphere_array", "--side", str(sphere_array_side(16, 0.125)), "--solid-fraction", "0.125"],
                     TAUS, (1.0, 1e-8)),
    "packing": ("random spheres, porosity 0.40, 10 voxels per diameter, 64^3",
                ["random", "--side", "64", "--radius", "5", "--solid-fraction", "0.6", "--seed", "7"], TAUS,
                (1.0, 1e-8)),
    "fine": ("random spheres, porosity 0.40, 6 voxels per diameter, 64^3",
             ["random", "--side", "64", "--radius", "3", "--solid-fraction", "0.6", "--seed", "7"],
             [0.55, 0.6, 0.7, 0.8, 1.0, 1.5], (0.8, 1e-8)),
    "packing96": ("random spheres, porosity 0.40, 10 voxels per diameter, 96^3",
                  ["random", "--side", "96", "--radius", "5", "--solid-fraction", "0.6", "--seed", "7"],
                  [0.6, 0.8, 1.0], (0.8, 1e-7)),
    "dense": ("random spheres, porosity 0.26, 10 voxels per diameter, 48^3 (1-3 voxel throats)",
              ["random", "--side", "48", "--radius", "5", "--solid-fraction", "0.74", "--seed", "7"], TAUS,
              (1.0, 1e-8)),
}


def run(build, work, case, tau, tolerance):
    image = os.path.join(work, f"{case}.h5")
    kind, *options = CASES[case][1]
    run_cached([f"{build}/tests/lbm/make_lbm_image", kind, image, *options, "--voxel-size", "1"], work,
               outputs=[image], log=f"{case}.log")
    out = os.path.join(work, f"{case}_tau{tau:g}_tol{tolerance:g}")
    result = os.path.join(out, f"permeability_{case}_direction0.h5")
    ranks = os.environ.get("RANKS", "1")
    launcher = ["mpiexec", "--oversubscribe", "-n", ranks] if ranks != "1" else []
    run_cached([*launcher, stage(build, "lbm"), "--input", image, "--direction", "0",
                *settings_arguments([f'lbm.output_dir="{out}"', f"lbm.tau={tau}",
                                     'lbm.convergence.criterion="change"',
                                     f"lbm.convergence.tolerance={tolerance}", "lbm.max_steps=2000000"])],
               out, outputs=[result])
    g = read_permeability(result)
    force, chosen, runs = float(g["body_force"]), float(g["tau"]), g["runs"]
    # The periodic method's K11 = nu <j>_1 / F (docs/methods/lbm.md) from the direction's run.
    k11 = (chosen - 0.5) / 3 * float(runs["mean_momentum"].reshape(-1, 3)[0, 0]) / force
    return {"k11": k11, "seconds": float(runs["seconds"].sum()), "steps": int(runs["steps"].sum()),
            "reynolds": float(runs["reynolds"].max()), "body_force": force, "chosen_tau": chosen, "ranks": ranks}


def main():
    build, work, output = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    os.makedirs(output, exist_ok=True)
    table = RunTable(os.path.join(output, "lbm_tau.csv"), FIELDS)

    def get(case, tau, tolerance):
        row = table.find(lambda r: (r["case"], float(r["tau"]), float(r["tolerance"])) == (case, tau, tolerance))
        if row:
            return row
        row = {"case": case, "tau": tau, "tolerance": tolerance}
        row.update(run(build, work, case, tau, tolerance))
        return table.add(row)

    fig, (ax_steps, ax_error) = plt.subplots(1, 2, figsize=(12, 4.8))
    for case, (label, _, taus, (reference_tau, reference_tolerance)) in CASES.items():
        reference = float(get(case, reference_tau, reference_tolerance)["k11"])
        points = [get(case, tau, DEFAULT_TOLERANCE) for tau in taus]
        steps = [int(p["steps"]) for p in points]
        errors = [max(abs(float(p["k11"]) / reference - 1) * 100, 1e-6) for p in points]
        line = ax_steps.loglog(taus, steps, "o-", label=label)[0]
        ax_error.loglog(steps, errors, "o-", color=line.get_color())
        for tau, s, e in zip(taus, steps, errors):
            ax_error.annotate(f"{tau:g}", (s, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
        auto = get(case, AUTOMATIC, DEFAULT_TOLERANCE)
        auto_error = max(abs(float(auto["k11"]) / reference - 1) * 100, 1e-6)
        ax_steps.loglog([float(auto["chosen_tau"])], [int(auto["steps"])], "*", ms=14, color=line.get_color(),
                        markeredgecolor="k")
        ax_error.loglog([int(auto["steps"])], [auto_error], "*", ms=14, color=line.get_color(), markeredgecolor="k")
    ax_steps.plot([], [], "*", ms=12, color="w", markeredgecolor="k", label="automatic tau (lbm.tau = 0)")
    ax_steps.set_xlabel("tau (lbm.tau)")
    ax_steps.set_ylabel("steps to convergence (tolerance 1e-5), axis x1")
    ax_steps.set_title("(a) cost against tau")
    ax_steps.legend(fontsize=7)
    ax_error.axhline(2.0, color="grey", ls=":", label="2%")
    ax_error.set_xlabel("steps to convergence (labels: tau)")
    ax_error.set_ylabel("|K11 / K11(tolerance 1e-8 or 1e-7) - 1| [%]")
    ax_error.set_title("(b) error against cost")
    fig.tight_layout()
    fig.savefig(os.path.join(output, "lbm_tau.png"), dpi=120)


if __name__ == "__main__":
    main_guarded(main)
