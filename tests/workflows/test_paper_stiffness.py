#!/usr/bin/python3
"""workflows/plots/stiffness.py shapes on synthetic probe and fabric CSVs whose numbers are known:
C11 - C33 = 4.1 K_C (H11 - H33)/(tr H/3) at every strain gives the ratio 4.10 and c1 = 1.000; a
probe in probes_unchecked/, or kept with checks_passed = 0, is drawn but left out of every number; MAX_STRAIN drops the later
checkpoints; a label may hold "="; probes that match no fabric row and a malformed argument stop
with a message.

usage: test_paper_stiffness.py SOURCE_DIR
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
SCRIPT = os.path.join(SOURCE, "workflows", "plots", "stiffness.py")
PYTHON = "/usr/bin/python3"
STRAINS = [2e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.3, 0.6]
RATIO = 4.1
K_C = 2.0e8


def h_anisotropy(strain):
    """(H11 - H33)/(tr H/3) rising and saturating, like a loading's; H22 - H33 half of it."""
    return 0.3 * strain / (strain + 0.01)


def write_probe(folder, stem, strain, a13, a23, K=K_C, checks_passed=1):
    """A probe CSV with (C11 - C33)/K_C = a13, (C22 - C33)/K_C = a23."""
    os.makedirs(folder, exist_ok=True)
    C = {"C_11": K * (1 + a13), "C_22": K * (1 + a23), "C_33": K}
    columns = ["source", "strain", "K_C", "checks_passed"] + [f"C_{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
    row = {"source": f"runs/x/relaxed/{stem}.h5", "strain": strain, "K_C": K, "checks_passed": checks_passed}
    row.update({f"C_{i}{j}": C.get(f"C_{i}{j}", 0.1 * K) for i in (1, 2, 3) for j in (1, 2, 3)})
    with open(os.path.join(folder, f"probe_{stem}.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        writer.writerow(row)


def write_fabric(path, stems):
    """H^c with the anisotropy above (tr H = 3); F, G and the strong forms: H's with a stem-dependent wobble."""
    names = ["H", "F", "G", "H_strong", "F_strong", "G_strong"]
    columns = ["source"] + [f"{n}_{i}{i}" for n in names for i in (1, 2, 3)]
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for k, (stem, strain) in enumerate(stems):
            a = h_anisotropy(strain)
            row = {"source": f"runs/x/relaxed/{stem}.h5"}
            for n, name in enumerate(names):
                wobble = 0 if name == "H" else 0.02 * ((k * (n + 1)) % 3 - 1)
                h11, h22 = 1 + a / 2 + wobble, 1 + a / 4 - wobble
                row.update({f"{name}_11": h11, f"{name}_22": h22, f"{name}_33": 3 - h11 - h22})
            writer.writerow(row)


def run(*args):
    return subprocess.run([PYTHON, SCRIPT, "shapes", *args], capture_output=True, text=True)


def table_rows(stdout, first_cell):
    return [[c.strip() for c in line.strip("|").split("|")] for line in stdout.splitlines()
            if line.startswith(f"| {first_cell}")]


class PaperStiffness(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        d = self.dir.name
        self.probes = os.path.join(d, "relaxed", "probes")
        stems = [(f"load_{k:03d}", s) for k, s in enumerate(STRAINS)]
        for stem, strain in stems:
            a = h_anisotropy(strain)
            # tr H = 3, so (H11 - H33)/(tr H/3) = H11 - H33 = 5a/4; C22 - C33 follows H22 - H33 = a.
            write_probe(self.probes, stem, strain, RATIO * 1.25 * a, RATIO * a)
        # A refused probe at a strain the checked ones lack, wildly off: it must not enter any number.
        write_probe(os.path.join(d, "relaxed", "probes_unchecked"), "load_008", 0.45, 50.0, -50.0)
        stems.append(("load_008", 0.45))
        self.fabric = os.path.join(d, "relaxed", "fabric_series.csv")
        write_fabric(self.fabric, stems)
        self.prefix = os.path.join(d, "chart")

    def tearDown(self):
        self.dir.cleanup()

    def test_ratio_and_correlations_of_a_proportional_stiffness(self):
        result = run(self.prefix, f"synthetic={self.probes},{self.fabric}")
        self.assertEqual(result.returncode, 0, result.stderr)
        (h,) = table_rows(result.stdout, "H^c |")
        c1, c2 = (float(v) for v in h[2].split("/"))
        self.assertAlmostEqual(c1, 1.0, delta=5e-4)
        self.assertAlmostEqual(c2, 1.0, delta=5e-4)
        (strong,) = table_rows(result.stdout, "H^c-strong")
        self.assertLess(float(strong[2].split("/")[0]), 0.999)  # the wobble lowers the others' c1
        (shape,) = table_rows(result.stdout, "synthetic")
        self.assertEqual(shape[1], "8")  # the unchecked probe is not counted
        self.assertEqual(shape[2], f"{RATIO * 1.25 * h_anisotropy(0.6):.2f} at 60%")
        ratio = shape[4].split()
        self.assertEqual(ratio[0], f"{RATIO:.2f}")
        self.assertEqual(ratio[1:], [f"({RATIO:.2f}", "-", f"{RATIO:.2f})"])
        for suffix in ("_C123.png", "_A.png"):
            self.assertGreater(os.path.getsize(self.prefix + suffix), 10_000)

    def test_a_probe_kept_with_failed_checks_is_left_out_of_every_number(self):
        # A campaign keeps a failed probe in the same folder with checks_passed = 0 (check_increment = false).
        write_probe(self.probes, "load_009", 0.5, -40.0, 40.0, checks_passed=0)
        with open(self.fabric, "a") as f:
            f.write("runs/x/relaxed/load_009.h5" + ",1" * 18 + "\n")
        result = run(self.prefix, f"synthetic={self.probes},{self.fabric}")
        self.assertEqual(result.returncode, 0, result.stderr)
        (shape,) = table_rows(result.stdout, "synthetic")
        self.assertEqual(shape[1], "8")
        ratio = shape[4].split()
        self.assertEqual(ratio[0], f"{RATIO:.2f}")

    def test_max_strain_keeps_the_earlier_checkpoints(self):
        result = run(self.prefix, f"early={self.probes},{self.fabric},0.06")
        self.assertEqual(result.returncode, 0, result.stderr)
        (shape,) = table_rows(result.stdout, "early")
        self.assertEqual(shape[1], "5")
        self.assertEqual(shape[2], f"{RATIO * 1.25 * h_anisotropy(0.05):.2f} at 5%")

    def test_a_label_may_hold_an_equals_sign(self):
        result = run(self.prefix, f"alpha = 0.5={self.probes},{self.fabric}")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(len(table_rows(result.stdout, "alpha = 0.5")), 1)

    def test_probes_matching_no_fabric_row_are_named(self):
        empty = os.path.join(self.dir.name, "empty.csv")
        write_fabric(empty, [])
        shutil.rmtree(os.path.join(self.dir.name, "relaxed", "probes_unchecked"))
        result = run(self.prefix, f"synthetic={self.probes},{empty}")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"synthetic: no probe in {self.probes} (or probes_unchecked beside it) matches a checkpoint "
                      f"of {empty}", result.stderr)

    def test_a_shape_with_only_refused_probes_is_drawn_without_numbers(self):
        refused = os.path.join(self.dir.name, "refused", "probes")
        os.makedirs(refused)
        write_probe(os.path.join(self.dir.name, "refused", "probes_unchecked"), "load_007", 0.6, 2.0, 1.0)
        result = run(self.prefix, f"refused={refused},{self.fabric}", f"synthetic={self.probes},{self.fabric}")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("n/a (0 checked probes)", table_rows(result.stdout, "H^c |")[0][2])
        self.assertEqual(table_rows(result.stdout, "refused")[0][1:], ["0", "n/a", "n/a", "n/a"])
        self.assertEqual(len(table_rows(result.stdout, "synthetic")), 1)

    def test_an_argument_without_its_fabric_series_stops_with_the_usage(self):
        result = run(self.prefix, f"synthetic={self.probes}")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("stiffness.py shapes OUTPUT_PREFIX", result.stderr)


if __name__ == "__main__":
    unittest.main()
