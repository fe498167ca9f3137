#!/usr/bin/python3
"""The paper's fabric figures (Kuhn, Sun & Wang 2015, section 3) for several particle shapes, from
the fabric series CSV of each run (aniso-fabric series, docs/formats/fabric.md):

  PREFIX_particles.png  Fig. 4 and 5: anisotropy (A11 - A33)/(tr A/3) of the particle orientation
                        J^p, the surface inertia I^s and the surface normals S^s, and (d) the
                        correlation of I^s and S^s with J^p for the flattest shape
  PREFIX_contacts.png   Fig. 6: F^c, H^c, H^c-strong (11 - 33) and the intermediate anisotropy
                        of H^c-strong (22 - 33), each with its small-strain range beside it
  PREFIX_stress.png     Fig. 7: (a) sigma11 - sigma33 against H^c-strong's 11 - 33 anisotropy,
                        (b) pi-plane paths of the stress (/p) and of 1.5 H^c-strong (/(tr/3)) for
                        the flattest shape
  PREFIX_voids_dem.png  the Minkowski tensor W3^{v,2,0} (normalized) and chi^v per particle

Strain is -eps11 in per cent. The script also prints the numbers the comparison quotes.

usage: paper_fabric.py PREFIX LABEL=FABRIC_SERIES.csv [LABEL=...]   (the flattest shape last)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from paper_fig3 import pi_plane  # noqa: E402

SMALL = 2.0  # per cent: the small-strain panels


def read_series(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    columns = {}
    for key in rows[0]:
        if key == "source":
            continue
        columns[key] = np.array([float(r[key]) for r in rows])
    columns["strain"] = -100 * columns["strain_11"]
    return columns


def anisotropy(s, name, pair="13"):
    return s[f"{name}_anisotropy_{pair}"]


def plot_pair(ax_full, ax_small, runs, name, pair, title):
    for label, s in runs:
        ax_full.plot(s["strain"], anisotropy(s, name, pair), "o-", ms=2.5, lw=0.8, label=label)
        small = s["strain"] <= SMALL
        ax_small.plot(s["strain"][small], anisotropy(s, name, pair)[small], "o-", ms=2.5, lw=0.8)
    ax_full.set_title(title, fontsize=9)
    ax_small.set_title(f"{title}, 0-{SMALL:g}%", fontsize=9)
    for ax in (ax_full, ax_small):
        ax.set_xlabel(r"strain $-\varepsilon_{11}$ [%]")
        ax.grid(alpha=0.3)


def particles_figure(prefix, runs):
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    for ax, name, symbol in ((axes[0, 0], "J", r"\overline{\mathbf{J}}^{\,p}"),
                             (axes[0, 1], "I", r"\overline{\mathbf{I}}^{\,s}"),
                             (axes[1, 0], "S", r"\overline{\mathbf{S}}^{\,s}")):
        for label, s in runs:
            ax.plot(s["strain"], anisotropy(s, name), "o-", ms=2.5, lw=0.8, label=label)
        ax.set_xlabel(r"strain $-\varepsilon_{11}$ [%]")
        ax.set_ylabel(rf"anisotropy 11-33 of ${symbol}$")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    label, s = runs[-1]
    ax = axes[1, 1]
    for name, marker in (("I", "o"), ("S", "s")):
        ax.plot(anisotropy(s, "J"), anisotropy(s, name), marker, ms=3.5, label=f"{name}$^s$")
    ax.set_xlabel(r"anisotropy 11-33 of $\overline{\mathbf{J}}^{\,p}$")
    ax.set_ylabel("anisotropy 11-33 of the surface tensor")
    ax.set_title(f"(d) surfaces against particle orientation, {label}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    for ax, letter in zip(axes.flat[:3], "abc"):
        ax.set_title(f"({letter}) " + {"a": "particle orientation", "b": "surface inertia",
                                       "c": "surface normals"}[letter], fontsize=9)
    fig.tight_layout()
    fig.savefig(f"{prefix}_particles.png", dpi=120)


def contacts_figure(prefix, runs):
    fig, axes = plt.subplots(4, 2, figsize=(10, 13), gridspec_kw={"width_ratios": [2, 1]})
    panels = (("F", "13", r"(a) $\overline{\mathbf{F}}^{\,c}$, $(F_{11}-F_{33})/(\mathrm{tr}F/3)$"),
              ("H", "13", r"(b) $\overline{\mathbf{H}}^{\,c}$, $(H_{11}-H_{33})/(\mathrm{tr}H/3)$"),
              ("H_strong", "13", r"(c) $\overline{\mathbf{H}}^{\,c\mathrm{-strong}}$, 11-33"),
              ("H_strong", "23", r"(d) $\overline{\mathbf{H}}^{\,c\mathrm{-strong}}$, intermediate 22-33"))
    for (name, pair, title), (ax_full, ax_small) in zip(panels, axes):
        plot_pair(ax_full, ax_small, runs, name, pair, title)
        ax_full.set_ylabel("anisotropy")
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}_contacts.png", dpi=120)


def stress_figure(prefix, runs):
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.8))
    for label, s in runs:
        deviator = (s["stress_33"] - s["stress_11"]) / 1e3  # compression positive, kPa
        ax_a.plot(anisotropy(s, "H_strong"), deviator, "o-", ms=2.5, lw=0.8, label=label)
    ax_a.set_xlabel(r"$(H^{c\mathrm{-strong}}_{11}-H^{c\mathrm{-strong}}_{33})\,/\,(\mathrm{tr}\,H/3)$")
    ax_a.set_ylabel(r"$\sigma_{11}-\sigma_{33}$ [kPa] (compression positive)")
    ax_a.set_title("(a) deviatoric stress against the strong mixed contact tensor", fontsize=9)
    ax_a.legend(fontsize=8)
    ax_a.grid(alpha=0.3)
    label, s = runs[-1]
    s1, s2, s3 = -s["stress_11"], -s["stress_22"], -s["stress_33"]
    x, y = pi_plane(s1, s2, s3, (s1 + s2 + s3) / 3)
    ax_b.plot(x, y, "o-", ms=3, lw=0.8, label=r"stress, $\sigma/p$")
    h1, h2, h3 = (s[f"H_strong_{k}{k}"] for k in (1, 2, 3))
    hx, hy = pi_plane(h1, h2, h3, (h1 + h2 + h3) / 3)
    ax_b.plot(1.5 * hx, 1.5 * hy, "s-", ms=3, lw=0.8, label=r"1.5 $\overline{\mathbf{H}}^{\,c\mathrm{-strong}}$ / (tr/3)")
    for angle, name in ((90, r"$x_1$"), (210, r"$x_2$"), (330, r"$x_3$")):
        a = np.radians(angle)
        ax_b.plot([0, 1.3 * np.cos(a)], [0, 1.3 * np.sin(a)], color="grey", lw=0.5)
        ax_b.annotate(name, (1.35 * np.cos(a), 1.35 * np.sin(a)), fontsize=8)
    ax_b.set_aspect("equal")
    ax_b.set_title(rf"(b) $\pi$-plane paths, {label} (radius: q/p)", fontsize=9)
    ax_b.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(f"{prefix}_stress.png", dpi=120)


def voids_figure(prefix, runs):
    fig, (ax_w, ax_chi) = plt.subplots(1, 2, figsize=(11, 4.3))
    for label, s in runs:
        ax_w.plot(s["strain"], anisotropy(s, "W320_normalized"), "o-", ms=2.5, lw=0.8, label=label)
        ax_chi.plot(s["strain"], s["chi_paper_per_particle"], "o-", ms=2.5, lw=0.8, label=label)
    ax_w.set_title(r"Minkowski tensor $\overline{\mathbf{W}}_3^{\,v,2,0}$, anisotropy 11-33", fontsize=9)
    ax_chi.set_title(r"void connectivity $\overline{\chi}^{\,v}=\chi^v/N^p$", fontsize=9)
    for ax in (ax_w, ax_chi):
        ax.set_xlabel(r"strain $-\varepsilon_{11}$ [%]")
        ax.grid(alpha=0.3)
    ax_w.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}_voids_dem.png", dpi=120)


def at(s, column, strain):
    return float(np.interp(strain, s["strain"], s[column]))


def summary(runs):
    print("shape | J 11-33: 0 / 2% / 60% | F^c: 0, peak (strain), 30%, 60% | H^c-strong and H^c at 0.1%, 0.5%, 2% "
          "| W3 at 0, 60% | chi/N at 0, 60%")
    for label, s in runs:
        f = anisotropy(s, "F")
        peak = int(np.argmax(f))
        print(f"{label} | {at(s, 'J_anisotropy_13', s['strain'][0]):.4f} / {at(s, 'J_anisotropy_13', 2):.4f} / "
              f"{at(s, 'J_anisotropy_13', 60):.4f} | {f[0]:.4f}, {f[peak]:.4f} ({s['strain'][peak]:.1f}%), "
              f"{at(s, 'F_anisotropy_13', 30):.4f}, {at(s, 'F_anisotropy_13', 60):.4f} | "
              + ", ".join(f"{at(s, 'H_strong_anisotropy_13', e):.3f}/{at(s, 'H_anisotropy_13', e):.3f}"
                          for e in (0.1, 0.5, 2))
              + f" | {at(s, 'W320_normalized_anisotropy_13', s['strain'][0]):.4f}, "
              f"{at(s, 'W320_normalized_anisotropy_13', 60):.4f} | {s['chi_paper_per_particle'][0]:.3f}, "
              f"{at(s, 'chi_paper_per_particle', 60):.3f}")
        for name in ("I", "S"):
            r = np.corrcoef(anisotropy(s, "J"), anisotropy(s, name))[0, 1]
            print(f"  {label}: {name}^s at 0 / 60%: {anisotropy(s, name)[0]:.4f} / {at(s, f'{name}_anisotropy_13', 60):.4f}; "
                  f"Pearson with J^p: {r:.3f}")


def main(prefix, runs):
    runs = [(label, read_series(path)) for label, path in runs]
    particles_figure(prefix, runs)
    contacts_figure(prefix, runs)
    stress_figure(prefix, runs)
    voids_figure(prefix, runs)
    summary(runs)


if __name__ == "__main__":
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], [tuple(a.rsplit("=", 1)) for a in sys.argv[2:]])
