#!/usr/bin/python3
"""The paper's void and permeability figures from a campaign's results.

voids.png (paper Figs. VoidDistrib, Lambda_vs_strain, R_vs_strain):
  (a) void-size distribution f_rho (ball opening, eq. (fr)) at the first and last voxelized checkpoint,
  (b) directed free-path distributions f_l_i (spar openings, eq. (fli)) at the same two checkpoints,
  (c) radial-breadth distributions f_r_i (disk openings, eq. (fri)) at the same two checkpoints,
  (d) L^v_11 - L^v_33 and L^v_22 - L^v_33 (eq. (Lambdaii)) and (e) the same for R^v (eq. (Rii)) against -eps11.
permeability.png (paper Fig. K_vs_strain): (K11 - K33)/tr K and (K22 - K33)/tr K against -eps11, and the
  diagonal of K against -eps11.
The numbers behind each go to voids.csv and permeability.csv beside them.

The loading strain of a result comes from the fabric series (fabric/fabric_series.h5, /checkpoints/<stem>),
matched by the checkpoint content hash (source_hash) each result records. The results are read from the
run folder's stage folders: voxel/voids_*.h5 and lbm/permeability_*.h5.

usage: void_flow_series.py RUN_FOLDER OUTPUT_FOLDER
"""
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

AXES = ("1", "2", "3")


def strain_by_hash(folder):
    """checkpoint content hash -> -eps11, from the fabric series of the run."""
    path = os.path.join(folder, "fabric", "fabric_series.h5")
    if not os.path.exists(path):
        sys.exit(f"void_flow_series.py: {path} is missing: the strains come from the fabric series")
    with h5py.File(path, "r") as f:
        return {g.attrs["source_hash"]: -float(g.attrs["strain_11"]) for g in f["checkpoints"].values()}


def strain_of(path, group, strains):
    with h5py.File(path, "r") as f:
        source_hash = f[group].attrs["source_hash"]
    if source_hash not in strains:
        sys.exit(f"void_flow_series.py: {path} comes from a checkpoint (hash {source_hash}) "
                 "that the fabric series does not hold")
    return strains[source_hash]


def read_voids(path):
    with h5py.File(path, "r") as f:
        g = f["voids"]
        out = {name: g[name][()] for name in ("L_v", "R_v", "porosity", "free_path_median", "breadth_median",
                                              "void_size_median")}
        out["curves"] = {}
        for name in ["ball"] + [f"{kind}_x{a}" for kind in ("spar", "disk") for a in AXES]:
            size = "length_d50" if name.startswith("spar") else "radius_d50"
            out["curves"][name] = (g[name][size][()], g[name]["fraction"][()])
        out["d50"] = float(g.attrs["d50"])
    return out


def draw_voids(folder, output, strains):
    paths = sorted(glob.glob(os.path.join(folder, "voxel", "voids_*.h5")))
    if not paths:
        return None
    results = sorted(((strain_of(p, "voids", strains), read_voids(p)) for p in paths), key=lambda r: r[0])
    strain = np.array([s for s, _ in results])
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    ends = [results[0], results[-1]] if len(results) > 1 else [results[0]]
    for (s, r), style in zip(ends, ["-", "--"]):
        label = f"{100 * s:.3g}%"
        sizes, fraction = r["curves"]["ball"]
        axes[0, 0].plot(sizes, fraction, style, color="k", label=label)
        for a, color in zip(AXES, ["C0", "C1", "C2"]):
            sizes, fraction = r["curves"][f"spar_x{a}"]
            axes[0, 1].plot(sizes, fraction, style, color=color, label=f"$x_{a}$, {label}")
            sizes, fraction = r["curves"][f"disk_x{a}"]
            axes[0, 2].plot(sizes, fraction, style, color=color, label=f"axis $x_{a}$, {label}")
    titles = [r"(a) void size $f_\rho$ (ball opening)", r"(b) free path $f_{\ell_i}$ (spar along $x_i$)",
              r"(c) radial breadth $f_{r_i}$ (disk, axis $x_i$)"]
    for ax, title in zip(axes[0], titles):
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("size / D50")
        ax.set_ylabel("fraction of the void kept")
        ax.legend(fontsize=7)
    axes[0, 1].set_xlim(0, 3)
    L = np.array([r["L_v"] for _, r in results])
    R = np.array([r["R_v"] for _, r in results])
    for ax, tensor, name in [(axes[1, 0], L, "L^v"), (axes[1, 1], R, "R^v")]:
        ax.plot(100 * strain, tensor[:, 0] - tensor[:, 2], "o-", label=f"${name}_{{11}} - {name}_{{33}}$")
        ax.plot(100 * strain, tensor[:, 1] - tensor[:, 2], "s--", label=f"${name}_{{22}} - {name}_{{33}}$")
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=8)
    axes[1, 0].set_title("(d) median free-path anisotropy, eq. (Lambdaii)", fontsize=9)
    axes[1, 1].set_title("(e) median radial-breadth anisotropy, eq. (Rii)", fontsize=9)
    porosity = np.array([r["porosity"] for _, r in results])
    axes[1, 2].plot(100 * strain, porosity, "ko-")
    axes[1, 2].set_title("porosity of the image", fontsize=9)
    axes[1, 2].set_xlabel(r"$-\varepsilon_{11}$ (%)")
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    with open(os.path.splitext(output)[0] + ".csv", "w") as out:
        out.write("strain,porosity,void_size_median_d50," + ",".join(f"free_path_median_{a}_d50" for a in AXES) + ","
                  + ",".join(f"breadth_median_{a}_d50" for a in AXES) + ","
                  + ",".join(f"L_v_{a}{a}" for a in AXES) + "," + ",".join(f"R_v_{a}{a}" for a in AXES) + "\n")
        for s, r in results:
            values = [s, r["porosity"], r["void_size_median"] / r["d50"], *(r["free_path_median"] / r["d50"]),
                      *(r["breadth_median"] / r["d50"]), *r["L_v"], *r["R_v"]]
            out.write(",".join(f"{v:.6g}" for v in values) + "\n")
    return results


def draw_permeability(folder, output, strains):
    paths = [p for p in sorted(glob.glob(os.path.join(folder, "lbm", "permeability_*.h5"))) if "_direction" not in p]
    if not paths:
        return None
    results = []
    for path in paths:
        with h5py.File(path, "r") as f:
            results.append((strain_of(path, "permeability", strains), f["permeability"]["K"][()],
                            float(f["permeability"].attrs["symmetry_error"])))
    results.sort(key=lambda r: r[0])
    strain = 100 * np.array([s for s, _, _ in results])
    diagonal = np.array([np.diag(K) for _, K, _ in results])
    trace = diagonal.sum(axis=1)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.plot(strain, (diagonal[:, 0] - diagonal[:, 2]) / trace, "o-", label=r"$(K_{11}-K_{33})/\mathrm{tr}\,K$")
    left.plot(strain, (diagonal[:, 1] - diagonal[:, 2]) / trace, "s--", label=r"$(K_{22}-K_{33})/\mathrm{tr}\,K$")
    left.axhline(0, color="0.5", lw=0.8)
    left.set_title("induced permeability anisotropy (paper Fig. K_vs_strain)", fontsize=9)
    for a in range(3):
        right.plot(strain, diagonal[:, a] * 1e12, "o-", label=f"$K_{{{a + 1}{a + 1}}}$")
    right.set_ylabel(r"$\mu$m$^2$")
    right.set_title("diagonal of the permeability tensor", fontsize=9)
    for ax in (left, right):
        ax.set_xlabel(r"$-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    with open(os.path.splitext(output)[0] + ".csv", "w") as out:
        out.write("strain,K11_m2,K22_m2,K33_m2,(K11-K33)/trK,(K22-K33)/trK,symmetry_error\n")
        for (s, K, symmetry), d, t in zip(results, diagonal, trace):
            out.write(f"{s:.6g},{d[0]:.6g},{d[1]:.6g},{d[2]:.6g},{(d[0] - d[2]) / t:.5f},{(d[1] - d[2]) / t:.5f},"
                      f"{symmetry:.3g}\n")
    return results


def main(folder, figures):
    strains = strain_by_hash(folder)
    os.makedirs(figures, exist_ok=True)
    draw_voids(folder, os.path.join(figures, "voids.png"), strains)
    draw_permeability(folder, os.path.join(figures, "permeability.png"), strains)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
