#!/usr/bin/python3
"""Paper Fig. 3 from a loading history: (a) (s11 - s33)/p, (b) (s22 - s33)/p,
(c) volumetric strain against -eps11, (d) the pi-plane stress path with radial
scale q/p; plus the mean-stress servo error and the coordination number.
Writes stress_strain.png and stress_strain.csv (the numbers behind the plot).

usage: stress_strain.py HISTORY.h5 OUTPUT_FOLDER
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402


def pi_plane(ax, s11, s22, s33, p):
    """(d): the deviator on the pi-plane, axes sigma_1..3 at 120 degrees; the radius of
    sum_i s_i e_i is q = sqrt(3 J2) for a traceless s, so dividing by p gives the radial scale q/p."""
    angles = np.radians([90.0, 210.0, 330.0])
    deviator = np.stack([s11 - p, s22 - p, s33 - p]) / p
    x = np.cos(angles) @ deviator
    y = np.sin(angles) @ deviator
    reach = 1.1 * max(np.hypot(x, y).max(), 0.1)
    for angle, name in zip(angles, [r"$\sigma_{11}$", r"$\sigma_{22}$", r"$\sigma_{33}$"]):
        ax.plot([0, reach * np.cos(angle)], [0, reach * np.sin(angle)], color="0.6", lw=0.8)
        ax.annotate(name, (reach * np.cos(angle), reach * np.sin(angle)), fontsize=9)
    for radius in np.arange(0.25, reach, 0.25):
        ax.add_patch(plt.Circle((0, 0), radius, fill=False, color="0.85", lw=0.6))
    ax.plot(x, y)
    ax.set_aspect("equal")
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_title("(d) pi-plane stress path, radial scale q/p (circles every 0.25)", fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def main(history_path, folder):
    h = read_history(history_path)
    strain = -h["strain_11"]
    p = h["p"]
    # Compression-positive principal stresses, as the paper plots them.
    s11, s22, s33 = -h["stress_11"], -h["stress_22"], -h["stress_33"]
    ratio_13 = (s11 - s33) / p
    ratio_23 = (s22 - s33) / p
    volumetric = h["volumetric_strain"]
    fig, axes = plt.subplots(2, 3, figsize=(13, 7))
    axes[0, 0].plot(100 * strain, ratio_13)
    axes[0, 0].set_ylabel(r"(a) $(\sigma_{11}-\sigma_{33})/p$")
    axes[0, 1].plot(100 * strain, ratio_23)
    axes[0, 1].set_ylabel(r"(b) $(\sigma_{22}-\sigma_{33})/p$")
    axes[0, 2].plot(100 * strain, 100 * volumetric)
    axes[0, 2].set_ylabel("(c) volumetric strain (%), dilation positive")
    axes[1, 1].plot(100 * strain, 100 * h["servo_error"])
    axes[1, 1].set_ylabel("mean-stress servo error (%)")
    axes[1, 2].plot(100 * strain, h["coordination"], label="all particles")
    axes[1, 2].plot(100 * strain, h["coordination_no_rattlers"], label="without rattlers")
    axes[1, 2].set_ylabel("coordination number")
    axes[1, 2].legend(fontsize=8)
    for ax in (axes[0, 0], axes[0, 1], axes[0, 2], axes[1, 1], axes[1, 2]):
        ax.set_xlabel(r"compressive strain $-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
    pi_plane(axes[1, 0], s11, s22, s33, p)
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
