#!/usr/bin/python3
"""workflows/plots/stress_strain.py signatures on a synthetic loading history whose signatures are known,
and stress_strain.py spread on two realisations of one shape (that history scaled by 1 and 5/6):
(sigma11 - sigma33)/p rises to 1.2 at 4%, holds to 6% and falls linearly to 0.9 at 60%; eps_v
falls to -0.5% at 2% and then rises linearly to +6.8% at 60%; the cell ends at x3 = 2.67 times
its width with eps11 = -0.60, so x1/x3 = 1.5 * 0.4 / 2.67 from an initial L1/L3 of 1.5. A
malformed argument and a non-numeric aspect stop with a message.

usage: test_paper_signatures.py SOURCE_DIR
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
SCRIPT = os.path.join(SOURCE, "workflows", "plots", "stress_strain.py")
PYTHON = "/usr/bin/python3"
P = 1.0e5


def ratio_at(s):
    return np.interp(s, [0.0, 0.04, 0.06, 0.60], [0.0, 1.2, 1.2, 0.9])


def eps_v_at(s):
    return np.interp(s, [0.0, 0.02, 0.60], [0.0, -0.005, 0.068])


def write_history(path, scale=1.0):
    strain = np.arange(0, 6001) * 1e-4
    ratio, eps_v = scale * ratio_at(strain), scale * eps_v_at(strain)
    # sigma33 = -p (1 - ratio/3) - ..., chosen so that (s33 - s11)/p = ratio with p fixed.
    s11 = -P * (1 + 2 * ratio / 3)
    s33 = -P * (1 - ratio / 3)
    e33 = np.linspace(0, 1.67, strain.size)
    columns = {"step": np.arange(strain.size), "strain_11": -strain, "strain_22": 0 * strain, "strain_33": e33,
               "volumetric_strain": eps_v, "stress_11": s11, "stress_22": -P + 0 * strain, "stress_33": s33,
               "p": P + 0 * strain, "void_ratio": np.linspace(0.556, 0.66, strain.size)}
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        writer.writerows(zip(*columns.values()))


class PaperSignatures(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp()
        self.history = os.path.join(self.work, "history.csv")
        write_history(self.history)

    def run_script(self, *args):
        return subprocess.run([PYTHON, SCRIPT, "signatures", *args], capture_output=True, text=True)

    def test_known_signatures(self):
        table = os.path.join(self.work, "signatures.csv")
        done = self.run_script("--csv", table, f"synthetic={self.history}@1.5")
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(table) as f:
            row = next(csv.DictReader(f))
        value = {k: float(v) for k, v in row.items() if k not in ("shape",) and v not in ("True", "False")}
        # The first 0.25% bin wholly on the plateau ends at 4.25%.
        self.assertAlmostEqual(value["peak"], 1.2, places=9)
        self.assertAlmostEqual(value["peak_strain"], 0.0425, places=9)
        # Bin means of a linear stretch: its value at the bin's centre (to the 1e-4 sampling).
        self.assertAlmostEqual(value["final_ratio"], ratio_at(0.59875), delta=1e-4)
        self.assertAlmostEqual(value["softening"], 1.2 - ratio_at(0.59875), delta=1e-4)
        self.assertAlmostEqual(value["ratio_20pc"], ratio_at(0.19875), delta=1e-4)
        self.assertAlmostEqual(value["eps_v_60pc"], eps_v_at(0.59875), delta=1e-5)
        self.assertAlmostEqual(value["min_eps_v"], -0.005, places=12)
        self.assertAlmostEqual(value["min_eps_v_strain"], 0.02, places=9)
        self.assertAlmostEqual(value["dilation_after_5pc"], eps_v_at(0.59875) - eps_v_at(0.04875), delta=1e-5)
        self.assertAlmostEqual(value["x3_growth"], 2.67, places=9)
        self.assertAlmostEqual(value["x1_over_x3"], 1.5 * 0.4 / 2.67, places=9)
        self.assertEqual(row["peak_in_paper_range"], "True")
        self.assertEqual(row["final_ratio_in_paper_range"], "True")
        self.assertIn("| synthetic | 1.200 (4.25%) |", done.stdout)

    def test_without_aspect_the_x1_x3_column_is_empty(self):
        done = self.run_script(f"synthetic={self.history}")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("| 2.670 |  | 0.", done.stdout)

    def test_bad_arguments_are_named(self):
        done = self.run_script(self.history)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("is not LABEL=HISTORY[@ASPECT]", done.stderr)
        done = self.run_script(f"x={self.history}@tall")
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("the initial L1/L3 'tall' is not a number", done.stderr)


class PaperSpread(unittest.TestCase):
    def test_two_realisations_give_their_mean_and_spread(self):
        work = tempfile.mkdtemp()
        paths = [os.path.join(work, f"h{k}.csv") for k in (1, 2)]
        write_history(paths[0], 1.0)
        write_history(paths[1], 5.0 / 6.0)  # peak 1.0
        prefix = os.path.join(work, "spread")
        done = subprocess.run([PYTHON, SCRIPT, "spread", prefix, f"spheres (realisation 1)={paths[0]}@1.5",
                               f"spheres (realisation 2)={paths[1]}@1.5", f"other={paths[0]}"],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        # Peaks 1.2 and 1.0: mean 1.1, sample standard deviation 0.2 / sqrt(2).
        self.assertIn("| spheres | 2 | 1.100 +- 0.141 (1.000 - 1.200) | 4.25% +- 0.00% (4.25% - 4.25%) |",
                      done.stdout)
        self.assertIn("| other | 1 | 1.200 | 4.25% |", done.stdout)
        self.assertGreater(os.path.getsize(prefix + ".png"), 10000)
        with open(prefix + ".csv") as f:
            rows = list(csv.DictReader(f))
        at_5 = next(r for r in rows if abs(float(r["strain"]) - 0.05) < 1e-9)
        self.assertAlmostEqual(float(at_5["spheres: ratio mean"]), 1.2 * (1 + 5 / 6) / 2, delta=1e-9)
        self.assertAlmostEqual(float(at_5["spheres: ratio std"]), 1.2 * (1 / 6) / np.sqrt(2), delta=1e-9)
        self.assertAlmostEqual(float(at_5["other: ratio std"]), 0.0, delta=0)


if __name__ == "__main__":
    unittest.main()
