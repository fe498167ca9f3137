#!/usr/bin/python3
"""The paper's figures and the comparison's numbers from campaign run folders (make paper).

For each run folder (docs/user-guide.md, "The run folder") the void and permeability CSVs go to
OUT/results/<slug>/ (voids.py csv); then every paper figure family is drawn into OUT/figures/ by
its script, and OUT/comparison.md gathers the figures with the numbers the scripts print:

  stress_strain.py signatures   peak, softening, large-strain ratio, dilation, the cell at 60%
  stress_strain.py spread       with several realisations of a shape: their mean and spread
  stress_strain.py fig3, shapes Fig. 3 (a-d); e and particle alignment
  fabric.py shapes              Figs. 4-7 and the DEM-side void measures (fabric series)
  fabric.py table2              Table 2: fabric-stress correlations averaged over the shapes
  stiffness.py shapes           Figs. C123 and A, c1/c2 and the stiffness-fabric ratio (probes)
  voids.py shapes               void distributions, anisotropies, permeability (voxel, LBM)

A family whose inputs some run lacks (a stage that was not built, or not given those checkpoints)
is left out with a line saying which file is missing; a script that fails stops the report with
its message and exit code. Labels come in the order given: the flattest shape last.

usage: paper_report.py OUT LABEL=RUN_FOLDER [LABEL=RUN_FOLDER ...]
"""
import os
import re
import subprocess
import sys

import h5py

PLOTS = os.path.dirname(os.path.abspath(__file__))
PYTHON = sys.executable or "/usr/bin/python3"


def pretty(label):
    """make paper's run names as the paper names them: 'ovoids-0.5' -> 'alpha = 0.5',
    'spheres-r2' -> 'spheres (realisation 2)'; other labels as given."""
    match = re.fullmatch(r"(spheres|ovoids-([0-9.]+))(-r([0-9]+))?", label)
    if not match:
        return label
    name = f"alpha = {match.group(2)}" if match.group(2) else "spheres"
    return name + (f" (realisation {match.group(4)})" if match.group(4) else "")


def slug(label):
    return re.sub(r"[^A-Za-z0-9.]+", "-", label).strip("-").lower()


def initial_aspect(run):
    """L1/L3 of the run's prepared cell (the paper's 1.5), for x1/x3 at the end."""
    with h5py.File(os.path.join(run, "dem", "prepared.h5"), "r") as f:
        lengths = f["cell/lengths"][()]
    return float(lengths[0] / lengths[2])


def script(name, *args):
    """Runs a plotting script; returns what it printed. A failure stops the report with its message."""
    done = subprocess.run([PYTHON, os.path.join(PLOTS, name), *args], capture_output=True, text=True)
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
        sys.exit(f"paper_report.py: {name} failed (exit {done.returncode})")
    return done.stdout


class Report:
    def __init__(self, out, runs):
        self.out, self.runs = out, runs
        self.figures = os.path.join(out, "figures")
        self.sections = []

    def missing(self, relative):
        """The first run folder that lacks `relative`, as a path (None when all have it)."""
        for _, run in self.runs:
            path = os.path.join(run, relative)
            if not (os.path.exists(path) and (not os.path.isdir(path) or os.listdir(path))):
                return path
        return None

    def section(self, title, images, text, source):
        self.sections.append((title, images, text, source))

    def left_out(self, title, path):
        self.sections.append((title, [], f"Not drawn: {path} is missing (that stage did not run there).\n", None))

    def stress_strain(self):
        histories = [f"{label}={run}/dem/history.h5" for label, run in self.runs]
        with_aspect = [f"{label}={run}/dem/history.h5@{initial_aspect(run):.12g}" for label, run in self.runs]
        table = script("stress_strain.py", "signatures", "--csv", os.path.join(self.figures, "signatures.csv"), *with_aspect)
        self.section("The paper's stress-strain signatures (section 4; the Digitized figure's text)", [], table,
                     "stress_strain.py signatures")
        if len({re.sub(r" \(realisation \d+\)$", "", label) for label, _ in self.runs}) < len(self.runs):
            table = script("stress_strain.py", "spread", os.path.join(self.figures, "spread"), *with_aspect)
            self.section("The spread between realisations", ["spread.png"], table, "stress_strain.py spread")
        script("stress_strain.py", "fig3", os.path.join(self.figures, "fig3.png"), *histories)
        script("stress_strain.py", "shapes", os.path.join(self.figures, "shapes"), *histories)
        self.section("Fig. 3: stress ratios, volume change and pi-plane paths", ["fig3.png", "shapes_stress_strain.png"], "",
                     "stress_strain.py fig3, shapes")

    def fabric(self):
        series = "fabric/fabric_series.csv"
        if (path := self.missing(series)) is not None:
            return self.left_out("Figs. 4-7: fabric", path)
        printed = script("fabric.py", "shapes", os.path.join(self.figures, "fabric"),
                         *[f"{label}={run}/{series}" for label, run in self.runs])
        images = [f"fabric_{k}.png" for k in ("particles", "contacts", "stress", "voids_dem")]
        self.section("Figs. 4-7: fabric", images, printed, "fabric.py shapes")
        correlations = "fabric/fabric_series_correlations.csv"
        if (path := self.missing(correlations)) is not None:
            return self.left_out("Table 2: fabric-stress correlations", path)
        table = script("fabric.py", "table2", *[f"{label}={run}/{correlations}" for label, run in self.runs])
        self.section("Table 2: fabric-stress correlations, averaged over the shapes", [], table, "fabric.py table2")

    def stiffness(self):
        for needed in ("probe", "fabric/fabric_series.csv"):
            if (path := self.missing(needed)) is not None:
                return self.left_out("Figs. C123 and A: stiffness", path)
        printed = script("stiffness.py", "shapes", os.path.join(self.figures, "stiffness"),
                         *[f"{label}={run}/probe,{run}/fabric/fabric_series.csv" for label, run in self.runs])
        self.section("Figs. C123 and A: incremental stiffness", ["stiffness_C123.png", "stiffness_A.png"], printed,
                     "stiffness.py shapes")

    def voids(self):
        if (path := self.missing("voxel")) is not None:
            return self.left_out("Voids and permeability", path)
        folders = []
        for label, run in self.runs:
            folder = os.path.join(self.out, "results", slug(label))
            script("voids.py", "csv", run, folder)
            folders.append(f"{label}={folder}")
        printed = script("voids.py", "shapes", os.path.join(self.figures, "voids"), *folders)
        images = [name for name in ("voids_distributions.png", "voids_anisotropy.png", "voids_permeability.png")
                  if os.path.exists(os.path.join(self.figures, name))]
        self.section("Voids (section 3.4) and permeability (section 5)", images, printed,
                     "voids.py csv, shapes")

    def write(self):
        lines = ["# The paper's study from one campaign", "",
                 "Generated by `workflows/plots/paper_report.py` from the run folders:", ""]
        lines += [f"- {label}: `{run}`" for label, run in self.runs]
        for title, images, text, source in self.sections:
            lines += ["", f"## {title}", ""]
            lines += [f"![{name}](figures/{name})" for name in images]
            if text:
                lines += ([""] if images else []) + [text.rstrip("\n")]
            if source:
                lines += ["", f"(`{source}`)"]
        path = os.path.join(self.out, "comparison.md")
        with open(path + ".tmp", "w") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(path + ".tmp", path)
        print(f"paper report: {path}")


def main(argv):
    if len(argv) < 2 or any("=" not in a for a in argv[1:]):
        sys.exit(__doc__)
    runs = [(pretty(label), run) for label, run in (a.rsplit("=", 1) for a in argv[1:])]
    for label, run in runs:
        if not os.path.exists(os.path.join(run, "dem", "history.h5")):
            sys.exit(f"paper_report.py: {label}: {run}/dem/history.h5 is missing: the run's load has not finished")
    report = Report(argv[0], runs)
    os.makedirs(report.figures, exist_ok=True)
    report.stress_strain()
    report.fabric()
    report.stiffness()
    report.voids()
    report.write()


if __name__ == "__main__":
    main(sys.argv[1:])
