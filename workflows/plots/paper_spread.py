#!/usr/bin/python3
"""The spread between realisations of each shape (make paper REALISATIONS=N): Fig. 3 (a) and (c),
(sigma11 - sigma33)/p and the volume change against strain, as each shape's mean over its
realisations with error bars of one standard deviation, and a table of the signatures
(paper_signatures.py) as mean +- standard deviation (min - max) over the realisations.

Labels "<shape> (realisation k)" group by <shape>; a label without it is a group of its own.
Curves are means over bins of 0.25% of strain (as paper_signatures.py), on the strains every
realisation of the shape reaches; error bars at every 2.5% of strain.

usage: paper_spread.py OUTPUT_PREFIX LABEL=HISTORY[@ASPECT] [LABEL=... ...]
  writes OUTPUT_PREFIX.png and OUTPUT_PREFIX.csv (the curves: strain, then per shape the mean and
  standard deviation of both quantities), and prints the Markdown table
"""
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402
from paper_signatures import BIN, bin_mean, parse, signatures  # noqa: E402

ERROR_BAR_EVERY = 0.025
SUMMARISED = [("peak", "peak", "{:.3f}"), ("peak_strain", "strain at the peak", "{:.2%}"),
              ("final_ratio", "ratio at the end", "{:.3f}"), ("softening", "softening", "{:.3f}"),
              ("eps_v_60pc", "eps_v at 60%", "{:+.2%}"), ("x3_growth", "x3 growth", "{:.3f}"),
              ("void_ratio_final", "e at the end", "{:.4f}")]


def group_of(label):
    match = re.fullmatch(r"(.*) \(realisation \d+\)", label)
    return match.group(1) if match else label


def curves(history):
    strain = -history["strain_11"]
    ratio = (history["stress_33"] - history["stress_11"]) / history["p"]
    ends = np.arange(BIN, strain[-1] + 1e-9, BIN)
    return ends, np.array([bin_mean(strain, ratio, e) for e in ends]), \
        np.array([bin_mean(strain, history["volumetric_strain"], e) for e in ends])


def spread(values, fmt):
    values = np.asarray(values, dtype=float)
    if values.size == 1:
        return fmt.format(values[0])
    return f"{fmt.format(values.mean())} +- {fmt.format(values.std(ddof=1))} " \
           f"({fmt.format(values.min())} - {fmt.format(values.max())})"


def main(prefix, arguments):
    groups = {}
    for label, path, aspect in map(parse, arguments):
        history = read_history(path)
        groups.setdefault(group_of(label), []).append((curves(history), signatures(history, aspect)))
    figure, (ax_ratio, ax_volume) = plt.subplots(1, 2, figsize=(12, 4.5))
    columns, table = {}, ["| shape | realisations | " + " | ".join(t for _, t, _ in SUMMARISED) + " |",
                          "|" + " --- |" * (2 + len(SUMMARISED))]
    for k, (shape, members) in enumerate(groups.items()):
        n = min(len(c[0]) for c, _ in members)
        strain = members[0][0][0][:n]
        ratio = np.array([c[1][:n] for c, _ in members])
        volume = np.array([c[2][:n] for c, _ in members])
        columns["strain"] = strain if "strain" not in columns or len(strain) < len(columns["strain"]) \
            else columns["strain"]
        every = max(1, int(round(ERROR_BAR_EVERY / BIN)))
        for ax, values in ((ax_ratio, ratio), (ax_volume, 100 * volume)):
            mean = values.mean(axis=0)
            deviation = values.std(axis=0, ddof=1) if len(members) > 1 else np.zeros_like(mean)
            line, = ax.plot(100 * strain, mean, color=f"C{k}", label=f"{shape} ({len(members)})")
            ax.errorbar(100 * strain[every - 1::every], mean[every - 1::every], yerr=deviation[every - 1::every],
                        fmt="none", ecolor=line.get_color(), capsize=2, lw=0.8)
        columns[f"{shape}: ratio mean"] = ratio.mean(axis=0)
        columns[f"{shape}: ratio std"] = ratio.std(axis=0, ddof=1) if len(members) > 1 else 0 * strain
        columns[f"{shape}: eps_v mean"] = volume.mean(axis=0)
        columns[f"{shape}: eps_v std"] = volume.std(axis=0, ddof=1) if len(members) > 1 else 0 * strain
        values = [[s[key] for _, s in members if key in s] for key, _, _ in SUMMARISED]
        cells = [spread(v, fmt) if v else "" for v, (_, _, fmt) in zip(values, SUMMARISED)]
        table.append(f"| {shape} | {len(members)} | " + " | ".join(cells) + " |")
    ax_ratio.set_ylabel(r"$(\sigma_{11} - \sigma_{33})/p$")
    ax_volume.set_ylabel(r"volumetric strain (%), dilation +")
    for ax, title in ((ax_ratio, "(a) stress ratio"), (ax_volume, "(c) volume change")):
        ax.set_xlabel(r"strain $-\varepsilon_{11}$ (%)")
        ax.set_title(f"{title}: mean of the realisations, bars one standard deviation")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(f"{prefix}.png", dpi=150)
    n = len(columns["strain"])
    with open(f"{prefix}.csv", "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(columns)
        writer.writerows(zip(*(np.asarray(v)[:n] for v in columns.values())))
    print("\n".join(table))


if __name__ == "__main__":
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
