#!/usr/bin/python3
"""Void ratio against compaction cycle for each shape (docs/charts/prepare_cycles.png, .csv).

Reads `aniso-dem prepare` logs: the void ratio at which each cycle seized, the
refinement re-runs, and the void ratio after consolidation to p0. Each log is
given as LABEL=PATH; the chart has one line per log, the target band
(target_void_ratio +- void_ratio_tolerance) and the consolidated e as a marker
at the kept cycle.

usage: chart_prepare_cycles.py OUTPUT_FOLDER TARGET TOLERANCE LABEL=LOG [LABEL=LOG ...]
"""
import csv
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CYCLE = re.compile(r"cycle +(\d+): seized after (\d+) steps at e = ([0-9.]+)")
REFINEMENT = re.compile(r"refinement (\d+) of cycle (\d+) .*seized after (\d+) steps at e = ([0-9.]+)")
CONSOLIDATED = re.compile(r"consolidated to p = \S+ Pa: e = ([0-9.]+)")
KEPT = re.compile(r"kept (?:cycle (\d+)|refinement (\d+) of cycle (\d+))")
RATTLERS = re.compile(r"Z = ([0-9.]+), Z without rattlers = ([0-9.]+) \((\d+) rattlers, ([0-9.]+)%\)")


def parse(path):
    """Returns the seized cycles [(cycle, steps, e)], refinements, the kept cycle and final state."""
    cycles, refinements, final = [], [], {}
    with open(path) as log:
        for line in log:
            if m := REFINEMENT.search(line):
                refinements.append((int(m[2]), int(m[1]), int(m[3]), float(m[4])))
            elif m := CYCLE.search(line):
                cycles.append((int(m[1]), int(m[2]), float(m[3])))
            if m := CONSOLIDATED.search(line):
                final["e"] = float(m[1])  # the last consolidation is the kept one
                if r := RATTLERS.search(line):
                    final.update(Z=float(r[1]), Z_nr=float(r[2]), rattler_percent=float(r[4]))
            if m := KEPT.search(line):
                final["kept_cycle"] = int(m[1] or m[3])
    if not cycles:
        raise SystemExit(f"{path}: no 'cycle N: seized after' lines: not an aniso-dem prepare log")
    return cycles, refinements, final


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    out, target, tolerance = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    runs = [arg.rsplit("=", 1) for arg in sys.argv[4:]]
    os.makedirs(out, exist_ok=True)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.axhspan(target - tolerance, target + tolerance, color="0.85", label="target +- tolerance")
    rows = []
    for label, path in runs:
        cycles, refinements, final = parse(path)
        line, = ax.plot([c[0] for c in cycles], [c[2] for c in cycles], "o-", ms=3, label=label)
        for cycle, refinement, steps, e in refinements:
            ax.plot(cycle, e, "x", color=line.get_color(), ms=5)
            rows.append((label, cycle, refinement, steps, e, ""))
        for cycle, steps, e in cycles:
            rows.append((label, cycle, 0, steps, e, ""))
        if "e" in final and "kept_cycle" in final:
            ax.plot(final["kept_cycle"], final["e"], "*", color=line.get_color(), ms=10)
            rows.append((label, final["kept_cycle"], "", "", final["e"], "consolidated"))
        print(f"{label}: {len(cycles)} cycles, seized {cycles[0][2]:.4f} -> {cycles[-1][2]:.4f}, "
              f"{len(refinements)} refinements, {final}")
    ax.set_xlabel("compaction cycle")
    ax.set_ylabel("void ratio when seized (star: kept, after consolidation)")
    ax.set_title("aniso-dem prepare: e against cycle (x: refinement re-runs)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "prepare_cycles.png"), dpi=120)
    with open(os.path.join(out, "prepare_cycles.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["run", "cycle", "refinement", "steps", "void_ratio", "state"])
        writer.writerows(rows)


if __name__ == "__main__":
    main()
