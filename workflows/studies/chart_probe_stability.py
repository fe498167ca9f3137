#!/usr/bin/python3
"""Stability chart of the probe (docs/charts/probe_stability.png).

Probes one checkpoint with aniso-probe over a sweep of the increment delta, of the
increment's rate (inertial number) and of the hold before the stress is read, and charts
the directional moduli C_ii/K_C and the relative error of C against a reference run on the
plateau, with the increment checks that detect too large (linearity of the two half
increments, contacts made to slide) and too small (response against round-off) increments
and an unsettled reading. The numbers go to
probe_stability.csv beside the figure.

usage: chart_probe_stability.py ANISO_PROBE CHECKPOINT.h5 WORK_FOLDER OUTPUT_FOLDER
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from runner import main_guarded, run_cached, settings_arguments  # noqa: E402
from readers import read_probe  # noqa: E402

DEFAULTS = {"increment": 5e-5, "inertial_number": 1e-3, "hold_steps": 500}
INCREMENTS = [1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-6, 1e-5, 2e-5, 5e-5, 1e-4, 3e-4, 1e-3]
INERTIAL_NUMBERS = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
HOLDS = [100, 200, 500, 1000, 2000]
# The reference: on the plateau of all three sweeps, well inside both increment checks.
REFERENCE = {"increment": 1e-5, "inertial_number": 1e-3, "hold_steps": 500}


def relative_error(C, reference):
    """Frobenius norm of C - reference relative to the reference's."""
    return float(np.linalg.norm(C - reference) / np.linalg.norm(reference))


def run(binary, checkpoint, work, settings):
    """One probe; a finished run in its folder is reused, not redone."""
    tag = "_".join(f"{k}={v}" for k, v in sorted(settings.items()))
    folder = os.path.join(work, tag)
    stem = os.path.splitext(os.path.basename(checkpoint))[0]
    result = os.path.join(folder, f"probe_{stem}.h5")
    options = [f"probe.output_dir={folder}", "probe.check_increment=false",
               f"probe.window_steps={settings['hold_steps'] // 2}", *(f"probe.{k}={v}" for k, v in settings.items())]
    done = run_cached([binary, "run", "--input", checkpoint, *settings_arguments(options)], folder, outputs=[result])
    out = read_probe(result)
    out["wall"] = done.wall
    return out


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    binary, checkpoint, work, charts = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    os.makedirs(charts, exist_ok=True)
    reference = run(binary, checkpoint, work, REFERENCE)
    sweeps = {
        "increment": [run(binary, checkpoint, work, {**DEFAULTS, "increment": d}) for d in INCREMENTS],
        "inertial_number": [run(binary, checkpoint, work, {**DEFAULTS, "inertial_number": i})
                            for i in INERTIAL_NUMBERS],
        "hold_steps": [run(binary, checkpoint, work, {**DEFAULTS, "hold_steps": h}) for h in HOLDS],
    }
    values = {"increment": INCREMENTS, "inertial_number": INERTIAL_NUMBERS, "hold_steps": HOLDS}
    labels = {"increment": r"increment $\delta = |d\varepsilon_{ii}|$",
              "inertial_number": "probe inertial number I", "hold_steps": "hold before reading [steps]"}

    rows = []
    fig, axes = plt.subplots(2, 4, figsize=(18, 7.5))
    for col, key in enumerate(("increment", "inertial_number", "hold_steps")):
        x = np.array(values[key], dtype=float)
        runs = sweeps[key]
        top, bottom = axes[0, col], axes[1, col]
        for i, colour in enumerate(("C0", "C1", "C2")):
            top.plot(x, [r["C"][i, i] / r["K_C"] for r in runs], "o-", color=colour,
                     label=f"$C_{{{i + 1}{i + 1}}}/K_C$")
        top.set_ylabel("$C_{ii}/K_C$")
        top.axvline(DEFAULTS[key], color="grey", ls=":", label="default")
        error = [relative_error(r["C"], reference["C"]) for r in runs]
        top.set_xscale("log")
        # The reference itself has error 0, which a log axis cannot show.
        bottom.plot(x, [e if e > 0 else np.nan for e in error], "ko-", label=r"$\|C - C_{ref}\| / \|C_{ref}\|$")
        bottom.plot(x, [r["linearity"] for r in runs], "s--", color="C3", label="linearity of the halves (<= 1)")
        bottom.plot(x, [max(r["sliding"], 1e-4) for r in runs], "v--", color="C5",
                    label="contacts made to slide (<= 0.1)")
        bottom.plot(x, [r["noise"] for r in runs], "^--", color="C4", label="reading noise (<= 0.25)")
        bottom.plot(x, [r["resolution"] for r in runs], "d--", color="C6", label="response / stress (>= 1e-9)")
        for level, colour in ((1.0, "C3"), (0.1, "C5"), (0.25, "C4"), (1e-9, "C6")):
            bottom.axhline(level, color=colour, lw=0.8, ls=":")
        bottom.axvline(DEFAULTS[key], color="grey", ls=":")
        bottom.set_yscale("log")
        bottom.set_xscale("log")
        bottom.set_xlabel(labels[key])
        if col == 0:
            top.legend(fontsize=8)
            bottom.legend(fontsize=8)
        for v, r, e in zip(x, runs, error):
            rows.append((key, v, r["K_C"], *(r["C"][i, i] / r["K_C"] for i in range(3)),
                         np.abs(r["D"]).max() / r["K_C"], e, r["linearity"], r["sliding"], r["noise"], r["resolution"],
                         r["steps_per_fork"], r["wall"]))
    # Speed/accuracy: cost of one fork against the error of C, over the rate and hold sweeps.
    cost = axes[0, 3]
    for key, marker in (("inertial_number", "o"), ("hold_steps", "s"), ("increment", "^")):
        for v, r in zip(values[key], sweeps[key]):
            e = relative_error(r["C"], reference["C"])
            cost.loglog(r["steps_per_fork"], max(e, 1e-3), marker, color={"inertial_number": "C0", "hold_steps": "C1",
                                                                        "increment": "C2"}[key])
            cost.annotate(f"{v:g}", (r["steps_per_fork"], max(e, 1e-3)), fontsize=7)
    cost.plot([], [], "o", color="C0", label="rate (I)")
    cost.plot([], [], "s", color="C1", label="hold [steps]")
    cost.plot([], [], "^", color="C2", label="increment")
    cost.set_xlabel("cost: steps per fork (7 forks per probe)")
    cost.set_ylabel("error of C against the reference")
    cost.set_title("speed / accuracy")
    cost.legend(fontsize=8)
    axes[1, 3].axis("off")
    axes[1, 3].text(0.0, 0.5, "defaults: " + ", ".join(f"{k} = {v:g}" for k, v in DEFAULTS.items())
                    + "\nchecks: too large if linearity > 1 or sliding > 0.1,\ntoo small if response/stress < 1e-9,"
                    "\nreading unsettled if noise > 0.25", fontsize=9)
    axes[0, 0].set_title("increment (rate and hold at defaults)")
    axes[0, 1].set_title("rate of the increment")
    axes[0, 2].set_title("hold before the reading")
    fig.suptitle(f"probe stability: {checkpoint} (strain {reference['strain']:.3g}); "
                 f"reference {REFERENCE}", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(charts, "probe_stability.png"), dpi=110)

    header = ("sweep,value,K_C,C11/K_C,C22/K_C,C33/K_C,max|D|/K_C,error_C,linearity,sliding,noise,resolution,"
              "steps_per_fork,wall_s")
    with open(os.path.join(charts, "probe_stability.csv"), "w") as f:
        f.write(header + "\n")
        for row in rows:
            f.write(",".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in row) + "\n")
    print(header)
    for row in rows:
        print(",".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in row))


if __name__ == "__main__":
    main_guarded(main)
