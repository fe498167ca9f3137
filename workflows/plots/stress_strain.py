#!/usr/bin/python3
"""Paper Fig. 3 from a loading history: (a) (s11 - s33)/p, (b) (s22 - s33)/p,
(c) volumetric strain, (d) mean-stress servo error, all against -eps11.
Writes stress_strain.png and stress_strain.csv (the numbers behind the plot).

usage: stress_strain.py HISTORY.h5 OUTPUT_FOLDER
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402


def main(history_path, folder):
    h = read_history(history_path)
    strain = -h["strain_11"]
    p = h["p"]
    # Compression-positive principal stresses, as the paper plots them.
    s11, s22, s33 = -h["stress_11"], -h["stress_22"], -h["stress_33"]
    ratio_13 = (s11 - s33) / p
    ratio_23 = (s22 - s33) / p
    volumetric = h["volumetric_strain"]
    fig, axes = plt.subplots(2, 2, figsize=(9, 7))
    axes[0, 0].plot(100 * strain, ratio_13)
    axes[0, 0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[0, 1].plot(100 * strain, ratio_23)
    axes[0, 1].set_ylabel(r"$(\sigma_{22}-\sigma_{33})/p$")
    axes[1, 0].plot(100 * strain, 100 * volumetric)
    axes[1, 0].set_ylabel("volumetric strain (%), dilation positive")
    axes[1, 1].plot(100 * strain, 100 * h["servo_error"])
    axes[1, 1].set_ylabel("mean-stress servo error (%)")
    for ax in axes.flat:
        ax.set_xlabel(r"compressive strain $-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
    fig.suptitle("Biaxial plane strain at constant p (paper Fig. 3)")
    fig.tight_layout()
    fig.savefig(f"{folder}/stress_strain.png", dpi=120)
    table = np.column_stack([strain, ratio_13, ratio_23, volumetric, h["void_ratio"], h["coordination"],
                             h["coordination_no_rattlers"], h["servo_error"], h["inertial_number"]])
    np.savetxt(f"{folder}/stress_strain.csv", table, delimiter=",",
               header="strain,ratio_13,ratio_23,volumetric_strain,void_ratio,coordination,"
                      "coordination_no_rattlers,servo_error,inertial_number", comments="")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
