#!/usr/bin/python3
"""Speed/accuracy chart of the LBM permeability (docs/charts/lbm_resolution_tolerance.png).

(a) Resolution: simple cubic sphere array at solid fraction 0.125 (Zick & Homsy 1982,
    k/a^2 = 0.41421) at several voxels per sphere diameter (the D50 of a monodisperse
    packing), double and single precision: error of K11 against the reference next to the
    wall time of the three runs.
(b) Convergence tolerance: the same cell at 12 voxels per diameter with the tolerance from
    1e-3 to 1e-6: deviation from the run at 1e-7 next to wall time.
Every run is a real aniso-lbm invocation; rows go to lbm_resolution_tolerance.csv, and runs
already listed there are reused (delete the csv to redo them).

usage: chart_lbm.py BUILD_FOLDER WORK_FOLDER OUTPUT_FOLDER
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from runner import RunTable, main_guarded, run_cached, settings_arguments, stage  # noqa: E402
from readers import read_permeability  # noqa: E402

PHI = 0.125
REFERENCE = 0.41421  # Zick & Homsy, k / a^2 at phi = 0.125
DIAMETERS = [8, 12, 16, 20]
FLOAT_DIAMETERS = [8, 12, 16]
TOLERANCES = [1e-3, 1e-4, 1e-5, 1e-6]
TIGHTEST = 1e-7
TOLERANCE_DIAMETER = 12
FIELDS = ["kind", "diameter", "precision", "tolerance", "side", "k11_over_a2", "seconds", "steps"]


def cell(diameter):
    side = round(diameter / 2 / (3 * PHI / (4 * math.pi)) ** (1 / 3))
    radius = side * (3 * PHI / (4 * math.pi)) ** (1 / 3)
    return side, radius


def run(build, work, diameter, precision, tolerance):
    side, radius = cell(diameter)
    image = os.path.join(work, f"cell_{side}.h5")
    run_cached([f"{build}/tests/lbm/make_lbm_image", "sphere_array", image, "--side", side, "--solid-fraction", PHI,
                "--voxel-size", "1"], work, outputs=[image], log=f"cell_{side}.log")
    out = os.path.join(work, f"d{diameter}_{precision}_{tolerance:g}")
    result = os.path.join(out, f"permeability_cell_{side}.h5")
    run_cached([stage(build, "lbm"), "--input", image,
                *settings_arguments([f'lbm.output_dir="{out}"', f'lbm.precision="{precision}"',
                                     'lbm.convergence.criterion="change"', f"lbm.convergence.tolerance={tolerance}", "lbm.tau=1.0", "lbm.body_force=1e-6"])],
               out, outputs=[result])
    g = read_permeability(result)
    k11 = g["K_lattice"][0, 0]
    seconds = float(g["runs"]["seconds"].sum())
    steps = int(g["runs"]["steps"].sum())
    return {"side": side, "k11_over_a2": k11 / radius ** 2, "seconds": seconds, "steps": steps}


def main():
    build, work, output = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    os.makedirs(output, exist_ok=True)
    table = RunTable(os.path.join(output, "lbm_resolution_tolerance.csv"), FIELDS)

    def get(kind, diameter, precision, tolerance):
        # The same run serves both panels (kind only says which panel asked first).
        row = table.find(lambda r: (int(r["diameter"]), r["precision"], float(r["tolerance"]))
                         == (diameter, precision, tolerance))
        if row:
            return row
        row = {"kind": kind, "diameter": diameter, "precision": precision, "tolerance": tolerance}
        row.update(run(build, work, diameter, precision, tolerance))
        return table.add(row)

    fig, (ax_res, ax_tol) = plt.subplots(1, 2, figsize=(11, 4.3))
    for precision, marker, diameters in (("double", "o", DIAMETERS), ("float", "s", FLOAT_DIAMETERS)):
        points = [get("resolution", d, precision, 1e-6) for d in diameters]
        errors = [abs(float(p["k11_over_a2"]) / REFERENCE - 1) * 100 for p in points]
        seconds = [float(p["seconds"]) for p in points]
        ax_res.loglog(seconds, errors, marker + "-", label=f"{precision}")
        for d, s, e in zip(diameters, seconds, errors):
            ax_res.annotate(f"{d}", (s, e), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax_res.axhline(2.0, color="grey", ls=":", label="2%")
    ax_res.set_xlabel("wall time of 3 runs [s] (labels: voxels per diameter)")
    ax_res.set_ylabel("|K11 / K(Zick & Homsy) - 1| [%]")
    ax_res.set_title(f"(a) resolution, sphere array, phi = {PHI}")
    ax_res.legend()

    reference = float(get("tolerance", TOLERANCE_DIAMETER, "double", TIGHTEST)["k11_over_a2"])
    points = [get("tolerance", TOLERANCE_DIAMETER, "double", t) for t in TOLERANCES]
    deviations = [max(abs(float(p["k11_over_a2"]) / reference - 1) * 100, 1e-7) for p in points]
    seconds = [float(p["seconds"]) for p in points]
    ax_tol.loglog(seconds, deviations, "o-", label="double")
    for t, s, e in zip(TOLERANCES, seconds, deviations):
        ax_tol.annotate(f"{t:g}", (s, e), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax_tol.set_xlabel("wall time of 3 runs [s] (labels: lbm.convergence.tolerance)")
    ax_tol.set_ylabel(f"|K11 / K(tol = {TIGHTEST:g}) - 1| [%]")
    ax_tol.set_title(f"(b) convergence tolerance, {TOLERANCE_DIAMETER} voxels per diameter")
    fig.tight_layout()
    fig.savefig(os.path.join(output, "lbm_resolution_tolerance.png"), dpi=120)


if __name__ == "__main__":
    main_guarded(main)
