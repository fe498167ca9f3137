#!/usr/bin/python3
"""workflows/paper_export.py's stage times on hand-written logs with known wall times: a stage's
timing lines summed over its runs (source "timing"); a run killed before its timing line counted by
its stamps beside the rerun's timing line (source "timing+stamps"); a log without one (aniso-voxel, -lbm and
-fabric built before they logged it) timed from its [HH:MM:SS] stamps, a silence of more than 10
minutes (a stopped or killed process) ending a stretch and a day added where the clock wraps
(source "stamps"); a log without either left out.

usage: test_paper_export_times.py SOURCE_DIR
"""
import csv
import os
import sys
import tempfile
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
sys.path.insert(0, os.path.join(SOURCE, "workflows"))

import paper_export  # noqa: E402


def stage_rows(logs):
    """stage_times over a run folder holding LOGS ({stage: text}), as {stage: row}."""
    with tempfile.TemporaryDirectory() as run:
        os.makedirs(os.path.join(run, "logs"))
        for stage, text in logs.items():
            with open(os.path.join(run, "logs", stage + ".log"), "w") as f:
                f.write(text)
        target = os.path.join(run, "stage_times.csv")
        paper_export.stage_times(run, target)
        with open(target) as f:
            return {row["stage"]: row for row in csv.DictReader(f)}


class StageTimes(unittest.TestCase):
    def test_timing_lines_of_all_runs_are_summed(self):
        log = ("[load] [10:00:00] info input 'x'\n[load] [10:05:00] info timing: 300.5 s wall on 2 rank(s)\n"
               "[load] [11:00:00] info input 'x'\n[load] [11:01:00] info timing: 60.25 s wall on 2 rank(s)\n")
        row = stage_rows({"load": log})["load"]
        self.assertEqual((float(row["wall_seconds"]), row["ranks"], row["runs"], row["source"]),
                         (360.8, "2", "2", "timing"))  # 360.75 written to 0.1 s

    def test_stamps_without_timing_lines(self):
        log = ("[lbm_x] [23:50:00] info input 'image.h5'\n[lbm_x] [23:55:00] info step 100\n"
               "[lbm_x] [00:02:00] info step 200\n"          # across midnight: 12 minutes in 2 lines of 7 and 5
               "[lbm_x] [00:30:00] info step 300\n"          # 28 minutes of silence: stopped, a new stretch
               "[lbm_x] [00:30:40] info wrote result\n")
        row = stage_rows({"lbm_x": log})["lbm_x"]
        self.assertEqual((float(row["wall_seconds"]), row["ranks"], row["runs"], row["source"]),
                         (12 * 60 + 40.0, "", "2", "stamps"))

    def test_a_run_killed_before_its_timing_line_counts_by_its_stamps(self):
        # The load killed at a session's end after 2 h, resumed 3 h later and finished in 1 h: the
        # timing line covers the last run alone.
        def progress(hour, minutes):
            return "".join(f"[load] [{hour + m // 60:02d}:{m % 60:02d}:00] info load: step\n" for m in minutes)
        log = (progress(4, range(0, 125, 5)) +      # 04:00 .. 06:00, killed
               progress(9, range(0, 60, 5)) + "[load] [10:00:00] info timing: 3600.4 s wall on 1 rank(s)\n")
        row = stage_rows({"load": log})["load"]
        self.assertEqual((float(row["wall_seconds"]), row["ranks"], row["runs"], row["source"]),
                         (10800.4, "1", "2", "timing+stamps"))

    def test_a_log_without_stamps_or_timing_is_left_out(self):
        rows = stage_rows({"odd": "no stamps here\n", "voxel_a": "[voxel_a] [01:00:00] info input\n"})
        self.assertNotIn("odd", rows)
        self.assertEqual(float(rows["voxel_a"]["wall_seconds"]), 0.0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
