#!/usr/bin/python3
"""The void and permeability scripts (workflows/plots/voids.py csv and shapes,
workflows/studies/permeability_checks_csv.py) on synthetic stage files whose numbers are known: the strain comes
from the checkpoint, the columns from the right datasets, the anisotropies and the direction files'
k = nu <j> / F are computed as documented, and a missing checkpoint is named.

usage: test_paper_voids.py SOURCE_DIR
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
PLOTS = os.path.join(SOURCE, "workflows", "plots")
STUDIES = os.path.join(SOURCE, "workflows", "studies")
PYTHON = "/usr/bin/python3"
D50 = 0.17e-3
CURVES = ["ball"] + [f"{kind}_x{a}" for kind in ("spar", "disk") for a in (1, 2, 3)]


def write_checkpoint(path, strain_11):
    with h5py.File(path, "w") as f:
        f["cell/reference_lengths"] = [2.0e-3, 1.5e-3, 1.5e-3]
        f["cell/lengths"] = [2.0e-3 * (1 + strain_11), 1.5e-3, 1.5e-3 * (1 - strain_11)]


def write_voids(path, scale):
    """Medians l_i = (1, 2, 3) scale d50 along x1..x3, r_i = (3, 2, 1) scale d50 / 10."""
    with h5py.File(path, "w") as f:
        g = f.create_group("voids")
        g.attrs["d50"] = D50
        free_path = np.array([1.0, 2.0, 3.0]) * scale * D50
        breadth = np.array([3.0, 2.0, 1.0]) * scale * D50 / 10
        g["free_path_median"] = free_path
        g["breadth_median"] = breadth
        g["L_v"] = 3 * free_path / free_path.sum()
        g["R_v"] = 3 * breadth / breadth.sum()
        g["porosity"] = 0.35 * scale
        g["void_size_median"] = 0.1 * D50 * scale
        for name in CURVES:
            size = "length_d50" if name.startswith("spar") else "radius_d50"
            g[f"{name}/{size}"] = np.array([0.0, 0.1, 0.2]) * scale
            g[f"{name}/fraction"] = [1.0, 0.5, 0.0]


def write_permeability(path, K):
    with h5py.File(path, "w") as f:
        g = f.create_group("permeability")
        g["K"] = np.array(K)
        g.attrs["porosity"] = 0.36
        g.attrs["tau"] = 0.55
        g.attrs["symmetry_error"] = 1e-5
        g.attrs["method"] = "periodic_body_force"
        g.attrs["voxel_size"] = 8.5e-6
        g["runs/axis"] = [1, 2, 3]
        g["runs/steps"] = [900, 1000, 1100]
        g["runs/reynolds"] = [0.01, 0.02, 0.03]
        g["runs/throat_width"] = [2.5, 3.0, 3.5]


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run(*arguments):
    return subprocess.run([PYTHON, *arguments], capture_output=True, text=True)


class PaperVoids(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.run_folder = os.path.join(self.tmp.name, "run")
        self.out = os.path.join(self.tmp.name, "out")
        for stage in ("dem", "voxel", "lbm"):
            os.makedirs(os.path.join(self.run_folder, stage))
        for stem, strain, scale in (("load_000", -2e-5, 1.0), ("load_001", -0.3, 1.2), ("load_002", -0.6, 1.1)):
            write_checkpoint(os.path.join(self.run_folder, "dem", f"{stem}.h5"), strain)
            write_voids(os.path.join(self.run_folder, "voxel", f"voids_{stem}.h5"), scale)
        self.K = {"load_000": np.diag([1.0, 2.0, 3.0]) * 1e-11, "load_002": np.diag([2.0, 2.0, 1.0]) * 1e-11}
        for stem, K in self.K.items():
            write_permeability(os.path.join(self.run_folder, "lbm", f"permeability_image_{stem}.h5"), K)

    def tearDown(self):
        self.tmp.cleanup()

    def collect(self):
        result = run(os.path.join(PLOTS, "voids.py"), "csv", self.run_folder, self.out)
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_void_rows_carry_the_checkpoint_strain_and_the_medians_in_d50(self):
        self.collect()
        rows = read_rows(os.path.join(self.out, "voids.csv"))
        self.assertEqual([r["checkpoint"] for r in rows], ["load_000", "load_001", "load_002"])
        self.assertAlmostEqual(float(rows[1]["strain_11"]), -0.3, delta=1e-12)
        self.assertAlmostEqual(float(rows[1]["free_path_median_3_d50"]), 3.6, delta=1e-7)
        self.assertAlmostEqual(float(rows[1]["breadth_median_1_d50"]), 0.36, delta=1e-7)
        self.assertAlmostEqual(float(rows[1]["L_v_11"]), 0.5, delta=1e-7)  # 3 * 1 / 6
        self.assertAlmostEqual(float(rows[1]["R_v_33"]), 0.5, delta=1e-7)

    def test_curves_are_kept_at_the_first_and_last_checkpoint_only(self):
        self.collect()
        rows = read_rows(os.path.join(self.out, "void_curves.csv"))
        self.assertEqual({r["checkpoint"] for r in rows}, {"load_000", "load_002"})
        self.assertEqual(len(rows), 2 * len(CURVES) * 3)
        disk = [r for r in rows if r["checkpoint"] == "load_002" and r["distribution"] == "disk_x2"]
        self.assertAlmostEqual(float(disk[2]["size_d50"]), 0.22, delta=1e-7)

    def test_permeability_anisotropy_is_the_difference_over_the_trace(self):
        self.collect()
        rows = {r["checkpoint"]: r for r in read_rows(os.path.join(self.out, "permeability.csv"))}
        self.assertEqual(set(rows), {"load_000", "load_002"})
        self.assertAlmostEqual(float(rows["load_000"]["K11_minus_K33_over_trace"]), -2 / 6, delta=1e-7)
        self.assertAlmostEqual(float(rows["load_002"]["K22_minus_K33_over_trace"]), 1 / 5, delta=1e-7)
        self.assertAlmostEqual(float(rows["load_002"]["strain_11"]), -0.6, delta=1e-12)
        self.assertEqual(rows["load_000"]["steps_3"], "1100")
        self.assertAlmostEqual(float(rows["load_000"]["throat_width_2_voxels"]), 3.0, delta=1e-12)

    def test_figures_are_drawn_and_the_correlations_printed(self):
        self.collect()
        prefix = os.path.join(self.tmp.name, "fig")
        result = run(os.path.join(PLOTS, "voids.py"), "shapes", prefix, f"alpha = 0.5={self.out}")
        self.assertEqual(result.returncode, 0, result.stderr)
        for suffix in ("distributions", "anisotropy", "permeability"):
            self.assertGreater(os.path.getsize(f"{prefix}_{suffix}.png"), 10000)
        # Two points per shape: the script prints the pooled lines only from three points on.
        self.assertIn("L11-L33", result.stdout)
        self.assertNotIn("Pearson", result.stdout)

    def test_a_missing_checkpoint_is_named(self):
        os.remove(os.path.join(self.run_folder, "dem", "load_001.h5"))
        result = run(os.path.join(PLOTS, "voids.py"), "csv", self.run_folder, self.out)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("load_001.h5 is missing", result.stderr)

    def test_no_void_results_is_refused(self):
        empty = os.path.join(self.tmp.name, "empty")
        os.makedirs(os.path.join(empty, "voxel"))
        result = run(os.path.join(PLOTS, "voids.py"), "csv", empty, self.out)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("run the campaign's voxel stage first", result.stderr)


class PermeabilityChecks(unittest.TestCase):
    def test_direction_files_give_nu_j_over_f_and_merge_by_label(self):
        with tempfile.TemporaryDirectory() as tmp:
            paths = []
            for axis, j in ((0, 4e-4), (2, 5e-4)):
                path = os.path.join(tmp, f"d{axis}.h5")
                with h5py.File(path, "w") as f:
                    g = f.create_group("direction")
                    g.attrs.update({"axis": axis, "tau": 0.8, "voxel_size": 1e-5, "body_force": 1e-4,
                                    "method": "paper_walls"})
                    g["runs/walls"] = [1, 2]  # no-slip, then free-slip (ignored)
                    momentum = np.zeros((2, 3))
                    momentum[0, axis] = j
                    momentum[1, axis] = 9.0
                    g["runs/mean_momentum"] = momentum
                paths.append(path)
            whole = os.path.join(tmp, "whole.h5")
            write_permeability(whole, np.diag([1.0, 2.0, 3.0]) * 1e-12)
            out = os.path.join(tmp, "checks.csv")
            result = run(os.path.join(STUDIES, "permeability_checks_csv.py"), out,
                         f"walls={paths[0]}", f"walls={paths[1]}", f"periodic={whole}")
            self.assertEqual(result.returncode, 0, result.stderr)
            rows = {r["label"]: r for r in read_rows(out)}
            nu = (0.8 - 0.5) / 3
            self.assertAlmostEqual(float(rows["walls"]["K_11"]) / (nu * 4e-4 / 1e-4 * 1e-10), 1, delta=1e-8)
            self.assertEqual(rows["walls"]["K_22"], "")
            self.assertAlmostEqual(float(rows["walls"]["K11_over_K33"]), 0.8, delta=1e-6)
            self.assertEqual(rows["walls"]["K11_minus_K33_over_trace"], "")
            self.assertAlmostEqual(float(rows["periodic"]["K11_minus_K33_over_trace"]), -2 / 6, delta=1e-6)


if __name__ == "__main__":
    unittest.main()
