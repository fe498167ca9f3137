#!/usr/bin/python3
"""Keep the committed rows of checkpoints that a rebuilt run folder no longer holds.

relaxed_csvs.sh KEEP_COMMITTED=1: a run folder lost with its host and rebuilt only in part (alpha = 0.8's
checkpoints to 10%, 2026-12-05) must not drop the committed rows of the checkpoints it lacks (the
critical state, relaxed from the first folder). Each row is one checkpoint and does not depend on the
others, so the new file gets the committed rows whose key it lacks, in key order. The two files must
have the same header (the same aniso-fabric), or nothing is written.

usage: merge_committed_rows.py NEW.csv COMMITTED.csv KEY_COLUMN
  rewrites NEW.csv in place; prints the keys taken from COMMITTED.csv
"""
import csv
import os
import re
import sys


def checkpoint_of(value):
    """load_014 from 'runs/paper-ovoids-0.8/relaxed/load_014.h5' or 'load_014'."""
    match = re.search(r"load_\d+", value)
    if not match:
        sys.exit(f"merge_committed_rows.py: '{value}' names no checkpoint load_NNN")
    return match.group(0)


def read(path, key):
    """(header line, {checkpoint: line}): lines kept as written (aniso-fabric quotes its file names)."""
    with open(path, newline="") as f:
        lines = [line for line in f.read().splitlines() if line]
    if not lines or key not in next(csv.reader([lines[0]])):
        sys.exit(f"merge_committed_rows.py: {path} has no column '{key}'")
    column = next(csv.reader([lines[0]])).index(key)
    return lines[0], {checkpoint_of(next(csv.reader([line]))[column]): line for line in lines[1:]}


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    new_path, committed_path, key = sys.argv[1:]
    new_header, new_rows = read(new_path, key)
    if not os.path.exists(committed_path):
        return
    committed_header, committed_rows = read(committed_path, key)
    if committed_header != new_header:
        sys.exit(f"merge_committed_rows.py: {committed_path} and {new_path} have different columns: "
                 "rerun the committed checkpoints instead")
    kept = sorted(set(committed_rows) - set(new_rows))
    merged = {**new_rows, **{k: committed_rows[k] for k in kept}}
    with open(new_path, "w") as f:
        f.write("\n".join([new_header] + [merged[k] for k in sorted(merged)]) + "\n")
    if kept:
        print(" ".join(kept))


if __name__ == "__main__":
    main()
