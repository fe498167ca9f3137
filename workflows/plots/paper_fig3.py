#!/usr/bin/python3
"""The paper's Fig. 3 for several particle shapes: (a) (sigma11 - sigma33)/p with a small-strain
inset, (b) (sigma22 - sigma33)/p, (c) volumetric strain, (d) the pi-plane stress paths with
radial scale q/p, q = sqrt(3 J2). Stresses compression positive; strain -eps11 in per cent.

usage: paper_fig3.py OUTPUT.png LABEL=HISTORY [LABEL=HISTORY ...]   (history.h5 or history.csv)
  e.g. paper_fig3.py docs/charts/paper_size_fig3.png spheres=docs/paper-size/spheres/history.csv ...
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from history_io import read_history  # noqa: E402


def principal(h):
    """Compression-positive sigma11, sigma22, sigma33, p and the strain in per cent."""
    s1, s2, s3 = -h["stress_11"], -h["stress_22"], -h["stress_33"]
    return s1, s2, s3, (s1 + s2 + s3) / 3, -100 * h["strain_11"]


def pi_plane(s1, s2, s3, p):
    """Coordinates of the deviatoric stress in the pi-plane, scaled by p: the radius is q/p,
    sigma1 up, sigma2 to the lower left and sigma3 to the lower right."""
    axes = [np.array([np.cos(a), np.sin(a)]) for a in np.radians([90, 210, 330])]
    scale = np.sqrt(3 / 2)  # |deviator| * sqrt(3/2) = q
    dev = [s - p for s in (s1, s2, s3)]
    x = sum(d * a[0] for d, a in zip(dev, axes)) * np.sqrt(2 / 3) * scale / p
    y = sum(d * a[1] for d, a in zip(dev, axes)) * np.sqrt(2 / 3) * scale / p
    return x, y


def main(output, runs):
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    (ax_a, ax_b), (ax_c, ax_d) = axes
    inset = ax_a.inset_axes([0.45, 0.12, 0.5, 0.42])
    for label, path in runs:
        h = read_history(path)
        s1, s2, s3, p, strain = principal(h)
        ax_a.plot(strain, (s1 - s3) / p, lw=0.8, label=label)
        small = strain <= 1.0
        inset.plot(strain[small], ((s1 - s3) / p)[small], lw=0.8)
        ax_b.plot(strain, (s2 - s3) / p, lw=0.8, label=label)
        ax_c.plot(strain, 100 * h["volumetric_strain"], lw=0.8, label=label)
        x, y = pi_plane(s1, s2, s3, p)
        ax_d.plot(x, y, lw=0.6, label=label)
    ax_a.set(xlabel=r"strain $-\varepsilon_{11}$ (%)", ylabel=r"$(\sigma_{11}-\sigma_{33})/p$",
             title="(a) deviatoric stress")
    inset.set(xlim=(0, 1), title="0-1%")
    inset.tick_params(labelsize=7)
    inset.title.set_fontsize(8)
    ax_b.set(xlabel=r"strain $-\varepsilon_{11}$ (%)", ylabel=r"$(\sigma_{22}-\sigma_{33})/p$",
             title="(b) intermediate deviatoric stress")
    ax_c.set(xlabel=r"strain $-\varepsilon_{11}$ (%)", ylabel=r"volumetric strain $\Delta V/V_0$ (%), dilation +",
             title="(c) volume change")
    # The pi-plane frame: the three principal axes and circles of q/p = 0.5 and 1.
    for angle, name in zip((90, 210, 330), (r"$\sigma_{11}$", r"$\sigma_{22}$", r"$\sigma_{33}$")):
        c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
        ax_d.plot([0, 1.3 * c], [0, 1.3 * s], color="0.7", lw=0.6)
        ax_d.text(1.38 * c, 1.38 * s, name, ha="center", va="center")
    for radius in (0.5, 1.0):
        t = np.linspace(0, 2 * np.pi, 200)
        ax_d.plot(radius * np.cos(t), radius * np.sin(t), color="0.85", lw=0.6)
    ax_d.set(aspect="equal", xlim=(-1.5, 1.5), ylim=(-1.0, 1.5), xticks=[], yticks=[],
             title=r"(d) $\pi$-plane paths, radius $q/p$ (circles 0.5, 1)")
    for ax in (ax_a, ax_b, ax_c):
        ax.grid(alpha=0.3)
        ax.set_xlim(0, 60)
    ax_a.legend(loc="upper left", fontsize=8)
    fig.suptitle("Biaxial plane strain at constant p = 100 kPa, 6400 particles (paper Fig. 3)")
    fig.tight_layout()
    fig.savefig(output, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) < 3 or any("=" not in arg for arg in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], [tuple(arg.rsplit("=", 1)) for arg in sys.argv[2:]])
