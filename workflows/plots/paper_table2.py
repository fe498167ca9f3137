#!/usr/bin/python3
"""Paper Table 2 from committed fabric series: the Pearson correlations c1 (of the 11 - 33
differences) and c2 (22 - 33) between six contact fabric tensors and the stress, averaged over
the particle shapes as the paper averages them over its four, beside the paper's values.
Prints a Markdown table (docs/paper-comparison.md).

usage: paper_table2.py LABEL=fabric_series_correlations.csv [LABEL=... ...]
  e.g. paper_table2.py spheres=docs/paper-size/spheres/fabric_series_correlations.csv ...
"""
import csv
import sys

# Kuhn, Sun & Wang (2015), Table 2, in its order (ranked by correlation).
PAPER = [("H_strong", 0.993, 0.988), ("F_strong", 0.941, 0.985), ("G_strong", 0.843, 0.979),
         ("H", 0.875, 0.840), ("F", 0.800, 0.810), ("G", 0.640, 0.842)]
SYMBOL = {"H_strong": "H^c-strong", "F_strong": "F^c-strong", "G_strong": "G^c-strong",
          "H": "H^c", "F": "F^c", "G": "G^c"}


def correlations(path):
    """{measure: (c1, c2)} of the fabric-stress rows of one shape."""
    with open(path) as f:
        return {row["measure"]: (float(row["c1"]), float(row["c2"]))
                for row in csv.DictReader(f) if row["against"] == "stress"}


def main(runs):
    shapes = [(label, correlations(path)) for label, path in runs]
    header = "| tensor | paper c1 | paper c2 | mean c1 | mean c2 | " + \
        " | ".join(f"{label} c1 / c2" for label, _ in shapes) + " |"
    print(header)
    print("|" + " --- |" * (5 + len(shapes)))
    for measure, paper_c1, paper_c2 in PAPER:
        values = [table[measure] for _, table in shapes]
        mean_c1 = sum(v[0] for v in values) / len(values)
        mean_c2 = sum(v[1] for v in values) / len(values)
        cells = " | ".join(f"{c1:.3f} / {c2:.3f}" for c1, c2 in values)
        print(f"| {SYMBOL[measure]} | {paper_c1:.3f} | {paper_c2:.3f} | {mean_c1:.3f} | {mean_c2:.3f} | {cells} |")


if __name__ == "__main__":
    if len(sys.argv) < 2 or any("=" not in arg for arg in sys.argv[1:]):
        sys.exit(__doc__)
    main([tuple(arg.rsplit("=", 1)) for arg in sys.argv[1:]])
