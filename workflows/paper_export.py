#!/usr/bin/python3
"""The small results of a `make paper` run, copied where the docs keep them (`make paper-export`,
workflows/paper.mk; docs/paper-size/ by default), so that every number of docs/paper-comparison.md
comes from one run and is rebuilt by one command.

For each run NAME=RUN_FOLDER (the shape, or <shape>-r<k> with several realisations) it writes
EXPORT/NAME/:
  history.csv                      the loading history (dem/history.csv)
  fabric_series.csv, fabric_series_correlations.csv   the fabric series of every checkpoint
  probes.csv                       every checkpoint's probe row (probe/probe_load_NNN.csv, in
                                   checkpoint order; checks_passed = 0 marks a probe whose checks failed)
  static_states.csv                per checkpoint: the loading's step it was copied at, the copy's
                                   relaxation steps, the steps it held static and whether the whole
                                   window held (the checkpoint's root attributes)
  voids.csv, void_curves.csv, permeability.csv   the void and permeability series (plots/voids.py csv)
  prepare.log                      the preparation's log (e against compaction cycle: studies/chart_prepare_cycles.py)
  stage_times.csv                  per stage of the campaign: wall seconds and ranks from its log
                                   (logs/<stage>.log), summed over its runs: a run's own timing line
                                   (source "timing"), or for a run killed before it wrote one, and
                                   for programs that did not log one yet, the span of its lines'
                                   time stamps (source "stamps"; "timing+stamps" for a mix); a pause
                                   of more than 10 minutes, a stopped or killed process, ends a run
and EXPORT/comparison.md and EXPORT/figures/ from PAPER_OUT (paper_report.py's output).
Files of an earlier export that this run does not make are left alone; every file it makes is replaced.

With --partial (`make paper-export-partial`, for a study still running) it exports what is there:
a run folder that does not exist yet is left out, a file not written yet (the history before the
first checkpoint, the fabric series, the comparison and figures before the end) is skipped with a
line saying so, and the series hold the checkpoints finished so far. A run on a host that may not
keep its folders loses no finished piece this way.

usage: paper_export.py [--partial] PAPER_OUT EXPORT NAME=RUN_FOLDER [NAME=RUN_FOLDER ...]
"""
import csv
import glob
import os
import re
import shutil
import sys

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "plots"))

from voids import csv_files  # noqa: E402

TIMING = re.compile(r"info timing: ([0-9.eE+-]+) s wall on (\d+) rank")
STAMP = re.compile(r"^\[[^\]]+\] \[(\d\d):(\d\d):(\d\d)\]", re.MULTILINE)
STAMP_GAP = 600  # seconds without a log line that end a run (stretches)


def fail(message):
    sys.exit(f"paper_export.py: {message}")


def copy(source, target, partial=False):
    """Copies SOURCE to TARGET; a missing SOURCE fails, or with `partial` is skipped (False returned)."""
    if not os.path.exists(source):
        if partial:
            print(f"paper_export.py: {source} not written yet, skipped")
            return False
        fail(f"{source} is missing: has the campaign finished?")
    shutil.copyfile(source, target + ".tmp")
    os.replace(target + ".tmp", target)
    return True


def write_rows(path, header, rows):
    with open(path + ".tmp", "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)
    os.replace(path + ".tmp", path)


def probes(run, target):
    paths = sorted(glob.glob(os.path.join(run, "probe", "probe_load_*.csv")))
    if not paths:
        return
    header, rows = None, []
    for path in paths:
        with open(path) as f:
            reader = csv.reader(f)
            first = next(reader)
            if header is not None and first != header:
                fail(f"{path}: its columns differ from {paths[0]}'s")
            header = first
            rows += list(reader)
    write_rows(target, header, rows)


def static_states(run, target):
    rows = []
    for path in sorted(glob.glob(os.path.join(run, "dem", "load_[0-9][0-9][0-9].h5"))):
        with h5py.File(path, "r") as f:
            a = f.attrs
            copied_at = int(a["relaxed_copy_of_step"]) if "relaxed_copy_of_step" in a else ""
            steps = int(a["step"]) - copied_at if copied_at != "" else ""
            rows.append([os.path.basename(path)[:-3], copied_at, steps, int(a.get("static_held_steps", 0)),
                         int(a.get("static_verified", 0)), f"{float(a['unbalanced_force_ratio']):.3e}"])
    write_rows(target, ["checkpoint", "copied_at_step", "relaxation_steps", "static_held_steps", "static_verified",
                        "unbalanced_force_ratio"], rows)


def stretches(text, gap=STAMP_GAP):
    """A log's runs as (stamp span in seconds, [(timing wall, ranks), ...]) per stretch of its lines'
    [HH:MM:SS] stamps, a stretch ending where the stamps stop for more than `gap` seconds (a killed
    run and its rerun, a stopped process) and a day added where the clock wraps."""
    found = []
    for line in text.splitlines():
        stamp = STAMP.match(line)
        if stamp is None:
            continue
        h, m, s = stamp.groups()
        timing = TIMING.search(line)
        found.append((3600 * int(h) + 60 * int(m) + int(s),
                      (float(timing.group(1)), int(timing.group(2))) if timing else None))
    runs = []
    for k, (stamp, timing) in enumerate(found):
        if k == 0 or (stamp - found[k - 1][0]) % 86400 > gap:
            runs.append([0, []])
        else:
            runs[-1][0] += (stamp - found[k - 1][0]) % 86400
        if timing is not None:
            runs[-1][1].append(timing)
    return runs


def stage_times(run, target):
    rows = []
    for path in sorted(glob.glob(os.path.join(run, "logs", "*.log"))):
        with open(path, errors="replace") as f:
            text = f.read()
        stage = os.path.basename(path)[:-4]
        runs = stretches(text)
        if not runs:
            continue
        # A stretch's wall time is its timing lines' sum (a run that finished; several when a rerun
        # followed within minutes) or, where that is less, its stamps' span (a run killed before its
        # timing line, alone or before a rerun): a stage resumed after a kill counts every run.
        seconds = sum(max(span, sum(w for w, _ in timings)) for span, timings in runs)
        timed = [timings for _, timings in runs if timings]
        ranks = max((r for timings in timed for _, r in timings), default="")
        source = "timing" if len(timed) == len(runs) else ("stamps" if not timed else "timing+stamps")
        rows.append([stage, f"{seconds:.1f}", ranks, sum(max(1, len(t)) for _, t in runs), source])
    write_rows(target, ["stage", "wall_seconds", "ranks", "runs", "source"], rows)


def export_run(name, run, folder, partial=False):
    os.makedirs(folder, exist_ok=True)
    copy(os.path.join(run, "dem", "history.csv"), os.path.join(folder, "history.csv"), partial)
    for stem in ("fabric_series", "fabric_series_correlations"):
        source = os.path.join(run, "fabric", f"{stem}.csv")
        if os.path.exists(source):
            copy(source, os.path.join(folder, f"{stem}.csv"))
    probes(run, os.path.join(folder, "probes.csv"))
    static_states(run, os.path.join(folder, "static_states.csv"))
    if glob.glob(os.path.join(run, "voxel", "voids_load_*.h5")):
        csv_files([run, folder])
    copy(os.path.join(run, "logs", "prepare.log"), os.path.join(folder, "prepare.log"), partial)
    stage_times(run, os.path.join(folder, "stage_times.csv"))
    print(f"paper_export.py: {name}: {run} -> {folder}")


def main(argv):
    partial = argv[:1] == ["--partial"]
    argv = argv[1:] if partial else argv
    if len(argv) < 3 or any("=" not in a for a in argv[2:]):
        sys.exit(__doc__)
    paper_out, export = argv[0], argv[1]
    for argument in argv[2:]:
        name, run = argument.split("=", 1)
        if not re.fullmatch(r"[A-Za-z0-9._-]+", name):
            fail(f"'{name}' is not a folder name (letters, digits, '.', '_', '-')")
        if partial and not os.path.isdir(run):
            print(f"paper_export.py: {name}: {run} not started, left out")
            continue
        export_run(name, run, os.path.join(export, name), partial)
    if not copy(os.path.join(paper_out, "comparison.md"), os.path.join(export, "comparison.md"), partial):
        return
    figures = os.path.join(export, "figures")
    os.makedirs(figures, exist_ok=True)
    for path in sorted(glob.glob(os.path.join(paper_out, "figures", "*"))):
        copy(path, os.path.join(figures, os.path.basename(path)))


if __name__ == "__main__":
    main(sys.argv[1:])
