#!/usr/bin/python3
"""The fabric figure family (Kuhn, Sun & Wang 2015, section 3: Figs. 4-7 and 11, Table 2) from
`aniso-fabric series` results (docs/formats/fabric.md). Anisotropy of a tensor A is
(A11 - A33)/(tr A/3); strain is -eps11 in per cent.

  fabric.py run FABRIC_SERIES.h5 OUTPUT_FOLDER
      one campaign run: fabric_anisotropy.png with the anisotropies of J^p (Fig. 4), I^s, S^s (Fig. 5),
      F^c, H^c, H^c-strong (Fig. 6a-c), W3 normalized (Fig. 11) and H^c-strong's 22 - 33 (Fig. 6d);
      fabric_stress.png with H^c-strong_11 - _33 against (s11 - s33)/p (Fig. 7a) and chi^v / N_p in both
      forms; fabric_correlations.csv with c1, c2 of each measure (Table 2)
  fabric.py shapes PREFIX LABEL=FABRIC_SERIES.csv [LABEL=...]   (the flattest shape last)
      several shapes: PREFIX_particles.png (Figs. 4 and 5: J^p, I^s, S^s, and the correlation of I^s and
      S^s with J^p for the flattest shape), PREFIX_contacts.png (Fig. 6: F^c, H^c, H^c-strong 11 - 33 and
      H^c-strong 22 - 33, each with its small-strain range beside it), PREFIX_stress.png (Fig. 7: (a)
      sigma11 - sigma33 against H^c-strong's 11 - 33, (b) the pi-plane paths of the stress (/p) and of
      1.5 H^c-strong (/(tr/3)) for the flattest shape), PREFIX_voids_dem.png (W3^{v,2,0} normalized and
      chi^v per particle); prints the numbers the comparison quotes
  fabric.py table2 LABEL=fabric_series_correlations.csv [LABEL=...]
      Table 2: the Pearson correlations c1 (11 - 33) and c2 (22 - 33) of six contact fabrics with the
      stress, averaged over the shapes as the paper averages them over its four, beside the paper's
      values, as a Markdown table
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cli import dispatch, labelled, output_and_labelled  # noqa: E402
from readers import read_correlations, read_fabric_series  # noqa: E402
from stress_strain import pi_plane  # noqa: E402


# --- one run: the campaign's figures --------------------------------------------------------------

PANELS = [("J", "Fig. 4"), ("I", "Fig. 5a"), ("S", "Fig. 5b"), ("F", "Fig. 6a"), ("H", "Fig. 6b"),
          ("H_strong", "Fig. 6c"), ("W320_normalized", "Fig. 11")]


def run_figures(arguments):
    if len(arguments) != 2:
        sys.exit(__doc__)
    path, folder = arguments
    s = read_fabric_series(path)
    correlations = s["correlations"]
    strain = -100 * s["strain_11"]
    fig, axes = plt.subplots(2, 4, figsize=(15, 7))
    for ax, (name, figure) in zip(axes.flat, PANELS):
        ax.plot(strain, s[f"{name}_anisotropy_13"], marker="o", ms=3)
        ax.set_title(f"{name}: (A11 - A33)/(tr A/3), paper {figure}", fontsize=9)
    ax = axes.flat[len(PANELS)]
    ax.plot(strain, s["H_strong_anisotropy_23"], marker="o", ms=3)
    ax.set_title("H_strong: (A22 - A33)/(tr A/3), paper Fig. 6d", fontsize=9)
    for ax in axes.flat:
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{folder}/fabric_anisotropy.png", dpi=110)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    ratio = (-s["stress_11"] + s["stress_33"]) / s["p"]
    axes[0].plot(s["H_strong_11"] - s["H_strong_33"], ratio, marker="o", ms=3)
    axes[0].set_xlabel(r"$H^{c-strong}_{11} - H^{c-strong}_{33}$")
    axes[0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[0].set_title("paper Fig. 7a", fontsize=9)
    axes[1].plot(strain, s["chi_paper_per_particle"], label=r"$1 + N_p - N_c$ (paper, eq. Chis1)")
    axes[1].plot(strain, s["chi_torus_per_particle"], label=r"$N_p - N_c + N_3 - N_4$ (periodic cell)")
    axes[1].set_xlabel(r"$-\varepsilon_{11}$ (%)")
    axes[1].set_ylabel(r"$\chi^v / N_p$")
    axes[1].legend(fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{folder}/fabric_stress.png", dpi=110)

    with open(f"{folder}/fabric_correlations.csv", "w") as out:
        out.write("measure,c1,c2,n_points\n")
        for name, a in sorted(correlations.items()):
            out.write(f"{name},{a['c1']:.4f},{a['c2']:.4f},{a['n_points']}\n")


# --- several shapes: the paper's figures ------------------------------------------------------

SMALL = 2.0  # per cent: the small-strain panels


def read_series(path):
    """A fabric_series.csv as columns, with the strain -eps11 in per cent."""
    columns = read_fabric_series(path)
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


def shape_figures(arguments):
    prefix, paths = output_and_labelled(arguments, __doc__)
    runs = [(label, read_series(path)) for label, path in paths]
    particles_figure(prefix, runs)
    contacts_figure(prefix, runs)
    stress_figure(prefix, runs)
    voids_figure(prefix, runs)
    summary(runs)


# --- Table 2 ---------------------------------------------------------------------------------

# Kuhn, Sun & Wang (2015), Table 2, in its order (ranked by correlation).
PAPER = [("H_strong", 0.993, 0.988), ("F_strong", 0.941, 0.985), ("G_strong", 0.843, 0.979),
         ("H", 0.875, 0.840), ("F", 0.800, 0.810), ("G", 0.640, 0.842)]
SYMBOL = {"H_strong": "H^c-strong", "F_strong": "F^c-strong", "G_strong": "G^c-strong",
          "H": "H^c", "F": "F^c", "G": "G^c"}


def table2(arguments):
    shapes = [(label, read_correlations(path)) for label, path in labelled(arguments, __doc__)]
    header = "| tensor | paper c1 | paper c2 | mean c1 | mean c2 | " + \
        " | ".join(f"{label} c1 / c2" for label, _ in shapes) + " |"
    print(header)
    print("|" + " --- |" * (5 + len(shapes)))
    for measure, paper_c1, paper_c2 in PAPER:
        values = [table[measure] for _, table in shapes]
        mean_c1 = sum(v[0] for v in values) / len(values)
        mean_c2 = sum(v[1] for v in values) / len(values)
        cells = " | ".join(f"{c1:.3f} / {c2:.3f}" for c1, c2 in values)
        print(f"| {SYMBOL[measure]} | {paper_c1:.3f} | {paper_c2:.3f} | {mean_c1:.3f} | {mean_c2:.3f} | {cells} |")


if __name__ == "__main__":
    dispatch({"run": run_figures, "shapes": shape_figures, "table2": table2}, __doc__, sys.argv[1:])
