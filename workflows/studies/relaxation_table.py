#!/usr/bin/python3
"""What `aniso-dem relax` changed at each checkpoint: the stress ratio q/p, the void ratio and the
coordination number (without rattlers) of the checkpoints as loaded and as relaxed, from two
fabric series (fabric_series.csv of the loaded checkpoints and of the relaxed ones, matched by
file name). Prints a Markdown table (docs/paper-comparison.md, section 4).

usage: relaxation_table.py LOADED_fabric_series.csv RELAXED_fabric_series.csv
"""
import csv
import os
import sys


def by_name(path):
    with open(path) as f:
        return {os.path.basename(row["source"]): row for row in csv.DictReader(f)}


def main(loaded_path, relaxed_path):
    loaded, relaxed = by_name(loaded_path), by_name(relaxed_path)
    names = sorted(set(loaded) & set(relaxed), key=lambda n: -float(relaxed[n]["strain_11"]))
    if not names:
        sys.exit(f"no checkpoint is in both {loaded_path} and {relaxed_path}")
    print("| checkpoint | strain (%) | q/p loaded | q/p relaxed | change | e loaded | e relaxed "
          "| Z loaded | Z relaxed |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name in names:
        a, b = loaded[name], relaxed[name]
        ratio_a = float(a["q"]) / float(a["p"])
        ratio_b = float(b["q"]) / float(b["p"])
        print(f"| {os.path.splitext(name)[0]} | {-100 * float(b['strain_11']):.3g} | {ratio_a:.3f} | {ratio_b:.3f} "
              f"| {100 * (ratio_b / ratio_a - 1):+.0f}% | {float(a['void_ratio']):.4f} | {float(b['void_ratio']):.4f} "
              f"| {float(a['coordination_no_rattlers']):.3f} | {float(b['coordination_no_rattlers']):.3f} |")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
