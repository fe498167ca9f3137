#!/usr/bin/python3
"""The campaign report: key numbers and the figures, one line of reading each.

usage: report.py RUN_FOLDER > report.md
"""
import sys

import numpy as np

from history_io import read_history


def main(folder):
    h = read_history(f"{folder}/history.h5")
    strain = -h["strain_11"]
    p = h["p"]
    ratio = (-h["stress_11"] + h["stress_33"]) / p
    peak = int(np.argmax(ratio))
    steady = strain > min(0.002, strain[-1] / 2)
    servo = np.abs(h["servo_error"][steady]) if steady.any() else np.abs(h["servo_error"])
    print("# aniso campaign report\n")
    print(f"Run folder: `{folder}`\n")
    print("## DEM: biaxial plane strain at constant mean stress\n")
    print("| quantity | value |\n| --- | --- |")
    print(f"| void ratio at the start of loading | {h['void_ratio'][0]:.4f} (paper: 0.556) |")
    print(f"| coordination number at start (without rattlers) | {h['coordination'][0]:.3f} "
          f"({h['coordination_no_rattlers'][0]:.3f}) |")
    print(f"| peak stress ratio (s11 - s33)/p | {ratio[peak]:.4f} at -eps11 = {100 * strain[peak]:.3g}% |")
    print(f"| final strain | {100 * strain[-1]:.3g}% |")
    print(f"| final void ratio | {h['void_ratio'][-1]:.4f} |")
    print(f"| mean-stress servo error after the first 0.2% strain: median, max | "
          f"{100 * np.median(servo):.3f}%, {100 * servo.max():.3f}% |")
    print(f"| inertial number (median) | {np.median(h['inertial_number']):.3g} |\n")
    print("![stress-strain](figures/stress_strain.png)\n")
    volumetric = h["volumetric_strain"]
    softening = ratio[-1] < 0.95 * ratio[peak]
    contraction = volumetric.min() < 0 and int(np.argmin(volumetric)) < len(volumetric) - 1
    dilates = volumetric[-1] > volumetric.min()
    print("Reading: the stress ratio " + ("peaks and then softens" if softening else "has not passed its peak")
          + f" by {100 * strain[-1]:.3g}% strain; the volume "
          + ("contracts first and then dilates" if contraction and dilates else
             "only dilates" if not contraction else "only contracts")
          + ". The paper's dense assemblies (its Fig. 3) peak and soften and dilate strongly beyond about 5% strain. "
          "The numbers behind the figure are in figures/stress_strain.csv.")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
