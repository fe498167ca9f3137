#!/usr/bin/python3
"""The paper's stress-strain signatures (Kuhn, Sun & Wang 2015, section 4 and the Digitized figure's
text) measured on loading histories, beside the paper's statements:

  - the peak of (sigma11 - sigma33)/p "at strains of 2-10%, followed by a softening";
  - (sigma11 - sigma33)/p at large strain "in the range 0.8-1.3 for the four particle shapes";
  - every shape dilating after 5% (its Fig. 3c);
  - alpha = 0.625 at eps11 = -0.60: x3 grown to 2.67 times its original width, x1/x3 = 0.22 from an
    initial 1.5, i.e. a volume change of 0.4 * 2.67 - 1 = +6.8%.

Values are means over the 0.25% of strain ending at the strain named (one path fluctuates from row
to row); the peak is the largest such mean, its strain the bin's end. Strain is -eps11.

usage: paper_signatures.py [--csv OUT.csv] LABEL=HISTORY[@ASPECT] [LABEL=... ...]
  HISTORY is a history.h5 or history.csv (docs/formats/history.md); ASPECT is the initial cell's
  L1/L3 (the paper's and the paper configs' 1.5), needed for x1/x3; without it that column is empty.
  Prints a Markdown table; --csv writes the same numbers.
"""
import csv
import sys

import numpy as np

from history_io import read_history

BIN = 0.0025
PAPER_PEAK_STRAIN = (0.02, 0.10)
PAPER_LARGE_STRAIN_RATIO = (0.8, 1.3)
REPORTED = [0.05, 0.10, 0.20, 0.60]


def bin_mean(strain, values, end):
    """Mean of values over the BIN of strain ending at `end` (NaN when no row lies there)."""
    inside = (strain > end - BIN) & (strain <= end + 1e-12)
    return float(values[inside].mean()) if inside.any() else float("nan")


def signatures(history, aspect=None):
    """The signature numbers of one history ({column: array}); strains as fractions."""
    strain = -history["strain_11"]
    ratio = (history["stress_33"] - history["stress_11"]) / history["p"]
    eps_v = history["volumetric_strain"]
    ends = np.arange(BIN, strain[-1] + 1e-9, BIN)
    means = np.array([bin_mean(strain, ratio, end) for end in ends])
    k = int(np.nanargmax(means))
    final = float(ends[-1])
    row = {"final_strain": final, "peak": float(means[k]), "peak_strain": float(ends[k]),
           "final_ratio": float(means[-1]), "softening": float(means[k] - means[-1])}
    for s in REPORTED:
        if s <= final + 1e-9:
            row[f"ratio_{100 * s:g}pc"] = bin_mean(strain, ratio, s)
            row[f"eps_v_{100 * s:g}pc"] = bin_mean(strain, eps_v, s)
    j = int(np.argmin(eps_v))
    row["min_eps_v"], row["min_eps_v_strain"] = float(eps_v[j]), float(strain[j]) + 0.0  # no -0
    # Dilation after 5%: eps_v at the end minus eps_v at 5% (the paper: all shapes dilate after 5%).
    row["dilation_after_5pc"] = float(bin_mean(strain, eps_v, final) - bin_mean(strain, eps_v, 0.05))
    # The cell: x3 (the free lateral axis) over its original width, and x1/x3 from the initial L1/L3.
    x3 = 1.0 + float(history["strain_33"][-1])
    x1 = 1.0 + float(history["strain_11"][-1])
    row["x3_growth"] = x3
    row["x1_over_x3"] = aspect * x1 / x3 if aspect else float("nan")
    row["void_ratio_final"] = float(history["void_ratio"][-1])
    row["peak_in_paper_range"] = PAPER_PEAK_STRAIN[0] <= row["peak_strain"] <= PAPER_PEAK_STRAIN[1]
    row["final_ratio_in_paper_range"] = PAPER_LARGE_STRAIN_RATIO[0] <= row["final_ratio"] <= PAPER_LARGE_STRAIN_RATIO[1]
    return row


def percent(value, digits=2, sign=True):
    return "" if np.isnan(value) else f"{100 * value:{'+' if sign else ''}.{digits}f}%"


def markdown(rows):
    lines = ["| shape | peak (strain) | ratio 10% | 20% | 60% | softening after the peak | eps_v 5% | 10% | 20% | "
             "60% | least eps_v (strain) | x3 growth | x1/x3 | e at the end |",
             "|" + " --- |" * 14]
    for label, r in rows:
        def at(key, fmt):
            return fmt(r[key]) if key in r else ""
        x1_x3 = "" if np.isnan(r["x1_over_x3"]) else f"{r['x1_over_x3']:.3f}"
        lines.append(
            f"| {label} | {r['peak']:.3f} ({percent(r['peak_strain'], 2, False)}) | {at('ratio_10pc', '{:.3f}'.format)} | "
            f"{at('ratio_20pc', '{:.3f}'.format)} | {at('ratio_60pc', '{:.3f}'.format)} | {r['softening']:.3f} | "
            f"{at('eps_v_5pc', percent)} | {at('eps_v_10pc', percent)} | {at('eps_v_20pc', percent)} | "
            f"{at('eps_v_60pc', percent)} | {percent(r['min_eps_v'])} ({percent(r['min_eps_v_strain'], 1, False)}) | "
            f"{r['x3_growth']:.3f} | {x1_x3} | "
            f"{r['void_ratio_final']:.4f} |")
    lines.append("| the paper | at 2-10%, then softening | | | 0.8-1.3 (all four) | > 0 | | | | all dilate after 5%; "
                 "alpha 0.625: +6.8% | | alpha 0.625: 2.67 | alpha 0.625: 0.22 | alpha 0.625 the smallest |")
    return "\n".join(lines)


def parse(argument):
    if "=" not in argument:
        sys.exit(f"paper_signatures.py: '{argument}' is not LABEL=HISTORY[@ASPECT]\n{__doc__}")
    label, path = argument.rsplit("=", 1)
    aspect = None
    if "@" in path:
        path, text = path.rsplit("@", 1)
        try:
            aspect = float(text)
        except ValueError:
            sys.exit(f"paper_signatures.py: '{argument}': the initial L1/L3 '{text}' is not a number")
    return label, path, aspect


def main(argv):
    out_csv = None
    if len(argv) >= 2 and argv[0] == "--csv":
        out_csv, argv = argv[1], argv[2:]
    if not argv:
        sys.exit(__doc__)
    rows = [(label, signatures(read_history(path), aspect)) for label, path, aspect in map(parse, argv)]
    print(markdown(rows))
    if out_csv:
        keys = list(dict.fromkeys(k for _, r in rows for k in r))
        with open(out_csv, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["shape"] + keys)
            for label, r in rows:
                writer.writerow([label] + [r.get(k, "") for k in keys])


if __name__ == "__main__":
    main(sys.argv[1:])
