#!/usr/bin/python3
"""The stress-strain figure family (Kuhn, Sun & Wang 2015, Fig. 3) from loading histories (history.h5 or
its history.csv twin). Stresses compression positive; strain -eps11 in per cent.

  stress_strain.py run HISTORY OUTPUT_FOLDER
      one run, the campaign's figure: (a) (sigma11 - sigma33)/p, (b) (sigma22 - sigma33)/p, (c) the
      volumetric strain, (d) the pi-plane path with radial scale q/p, the mean-stress servo error and the
      coordination number; OUTPUT_FOLDER/stress_strain.png and stress_strain.csv (the numbers behind it)
  stress_strain.py fig3 OUTPUT.png LABEL=HISTORY [LABEL=HISTORY ...]
      several runs on the paper's Fig. 3: (a) with its 0-1% inset, (b), (c), (d) the pi-plane paths
  stress_strain.py shapes OUTPUT_PREFIX LABEL=HISTORY [LABEL=HISTORY ...]
      several runs: (a), (c), the void ratio and the mean particle-axis orientation <a1 a1> (1/3 when
      isotropic); PREFIX_stress_strain.png and .csv, and one summary line per run
  stress_strain.py signatures [--csv OUT.csv] LABEL=HISTORY[@ASPECT] [LABEL=... ...]
      the paper's stress-strain signatures (section 4 and the Digitized figure's text) measured on each
      history, beside the paper's statements, as a Markdown table (--csv: the same numbers):
        - the peak of (sigma11 - sigma33)/p "at strains of 2-10%, followed by a softening";
        - (sigma11 - sigma33)/p at large strain "in the range 0.8-1.3 for the four particle shapes";
        - every shape dilating after 5% (Fig. 3c);
        - alpha = 0.625 at eps11 = -0.60: x3 grown to 2.67 times its original width, x1/x3 = 0.22 from
          an initial 1.5, i.e. a volume change of 0.4 * 2.67 - 1 = +6.8%.
      Values are means over the 0.25% of strain ending at the strain named (one path fluctuates from row
      to row); the peak is the largest such mean, its strain the bin's end. ASPECT is the initial cell's
      L1/L3 (the paper's and the paper configs' 1.5), needed for x1/x3; without it that column is empty.
  stress_strain.py spread OUTPUT_PREFIX LABEL=HISTORY[@ASPECT] [LABEL=... ...]
      the spread between realisations of each shape (make paper REALISATIONS=N): (a) and (c) as each
      shape's mean over its realisations with error bars of one standard deviation (every 2.5% of
      strain; 0.25% bin means on the strains every realisation reaches), OUTPUT_PREFIX.png and .csv, and
      the signatures as mean +- standard deviation (min - max) in a Markdown table. Labels "<shape>
      (realisation k)" group by <shape>; a label without it is a group of its own.
"""
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cli import dispatch, output_and_labelled  # noqa: E402
from readers import read_history  # noqa: E402

STRAIN_LABEL = r"strain $-\varepsilon_{11}$ (%)"
PI_AXES = np.radians([90.0, 210.0, 330.0])  # sigma1 up, sigma2 lower left, sigma3 lower right
PI_NAMES = (r"$\sigma_{11}$", r"$\sigma_{22}$", r"$\sigma_{33}$")


def principal(h):
    """Compression-positive sigma11, sigma22, sigma33, their mean p, and the strain -eps11 in per cent."""
    s1, s2, s3 = -h["stress_11"], -h["stress_22"], -h["stress_33"]
    return s1, s2, s3, (s1 + s2 + s3) / 3, -100 * h["strain_11"]


def pi_plane(s1, s2, s3, p):
    """The deviator's coordinates in the pi-plane, scaled by p: sum_i (s_i - p) e_i over unit axes 120 degrees
    apart has the radius q = sqrt(3 J2) of a traceless deviator, so the radius here is q/p."""
    deviator = np.stack([s1 - p, s2 - p, s3 - p]) / p
    return np.cos(PI_AXES) @ deviator, np.sin(PI_AXES) @ deviator


def pi_plane_frame(ax, reach, circles):
    """The three principal axes out to `reach` and circles of q/p at the radii `circles`."""
    for angle, name in zip(PI_AXES, PI_NAMES):
        ax.plot([0, reach * np.cos(angle)], [0, reach * np.sin(angle)], color="0.7", lw=0.6)
        ax.text(1.06 * reach * np.cos(angle), 1.06 * reach * np.sin(angle), name, ha="center", va="center")
    t = np.linspace(0, 2 * np.pi, 200)
    for radius in circles:
        ax.plot(radius * np.cos(t), radius * np.sin(t), color="0.85", lw=0.6)
    ax.set(aspect="equal", xticks=[], yticks=[])


def run_figure(arguments):
    if len(arguments) != 2:
        sys.exit(__doc__)
    history_path, folder = arguments
    h = read_history(history_path)
    s1, s2, s3, _, strain = principal(h)
    p = h["p"]
    ratio_13, ratio_23 = (s1 - s3) / p, (s2 - s3) / p
    volumetric = h["volumetric_strain"]
    fig, axes = plt.subplots(2, 3, figsize=(13, 7))
    axes[0, 0].plot(strain, ratio_13)
    axes[0, 0].set_ylabel(r"(a) $(\sigma_{11}-\sigma_{33})/p$")
    axes[0, 1].plot(strain, ratio_23)
    axes[0, 1].set_ylabel(r"(b) $(\sigma_{22}-\sigma_{33})/p$")
    axes[0, 2].plot(strain, 100 * volumetric)
    axes[0, 2].set_ylabel("(c) volumetric strain (%), dilation positive")
    axes[1, 1].plot(strain, 100 * h["servo_error"])
    axes[1, 1].set_ylabel("mean-stress servo error (%)")
    axes[1, 2].plot(strain, h["coordination"], label="all particles")
    axes[1, 2].plot(strain, h["coordination_no_rattlers"], label="without rattlers")
    axes[1, 2].set_ylabel("coordination number")
    axes[1, 2].legend(fontsize=8)
    for ax in (axes[0, 0], axes[0, 1], axes[0, 2], axes[1, 1], axes[1, 2]):
        ax.set_xlabel(STRAIN_LABEL)
        ax.grid(alpha=0.3)
    x, y = pi_plane(s1, s2, s3, p)
    reach = 1.1 * max(np.hypot(x, y).max(), 0.1)
    pi_plane_frame(axes[1, 0], reach, np.arange(0.25, reach, 0.25))
    axes[1, 0].plot(x, y)
    axes[1, 0].set(xlim=(-1.1 * reach, 1.1 * reach), ylim=(-1.1 * reach, 1.1 * reach))
    axes[1, 0].set_title("(d) pi-plane stress path, radial scale q/p (circles every 0.25)", fontsize=9)
    fig.suptitle("Biaxial plane strain at constant p (paper Fig. 3)")
    fig.tight_layout()
    fig.savefig(f"{folder}/stress_strain.png", dpi=120)
    table = np.column_stack([strain / 100, ratio_13, ratio_23, volumetric, h["void_ratio"], h["coordination"],
                             h["coordination_no_rattlers"], h["servo_error"], h["inertial_number"]])
    np.savetxt(f"{folder}/stress_strain.csv", table, delimiter=",",
               header="strain,ratio_13,ratio_23,volumetric_strain,void_ratio,coordination,"
                      "coordination_no_rattlers,servo_error,inertial_number", comments="")


def fig3(arguments):
    output, runs = output_and_labelled(arguments, __doc__)
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
    ax_a.set(xlabel=STRAIN_LABEL, ylabel=r"$(\sigma_{11}-\sigma_{33})/p$", title="(a) deviatoric stress")
    inset.set(xlim=(0, 1), title="0-1%")
    inset.tick_params(labelsize=7)
    inset.title.set_fontsize(8)
    ax_b.set(xlabel=STRAIN_LABEL, ylabel=r"$(\sigma_{22}-\sigma_{33})/p$", title="(b) intermediate deviatoric stress")
    ax_c.set(xlabel=STRAIN_LABEL, ylabel=r"volumetric strain $\Delta V/V_0$ (%), dilation +", title="(c) volume change")
    pi_plane_frame(ax_d, 1.3, (0.5, 1.0))
    ax_d.set(xlim=(-1.5, 1.5), ylim=(-1.0, 1.5), title=r"(d) $\pi$-plane paths, radius $q/p$ (circles 0.5, 1)")
    for ax in (ax_a, ax_b, ax_c):
        ax.grid(alpha=0.3)
        ax.set_xlim(0, 60)
    ax_a.legend(loc="upper left", fontsize=8)
    fig.suptitle("Biaxial plane strain at constant p = 100 kPa, 6400 particles (paper Fig. 3)")
    fig.tight_layout()
    fig.savefig(output, dpi=120)


def shape_curves(h):
    return {"strain": -h["strain_11"], "stress ratio": (h["stress_33"] - h["stress_11"]) / h["p"],
            "volumetric strain": h["volumetric_strain"], "void ratio": h["void_ratio"],
            "axis orientation 11": h["axis_orientation_11"]}


def shapes(arguments):
    prefix, runs = output_and_labelled(arguments, __doc__)
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    rows = []
    for label, path in runs:
        c = shape_curves(read_history(path))
        peak = int(np.argmax(c["stress ratio"]))
        for ax, name in zip(axes.flat, ["stress ratio", "volumetric strain", "void ratio", "axis orientation 11"]):
            ax.plot(100 * c["strain"], c[name], label=label, lw=1)
        rows += [[label] + [f"{c[k][i]:.6g}" for k in c] for i in range(len(c["strain"]))]
        print(f"{label}: e0 = {c['void ratio'][0]:.4f}, peak (s11 - s33)/p = {c['stress ratio'][peak]:.3f} at "
              f"{100 * c['strain'][peak]:.3g}%, at {100 * c['strain'][-1]:.3g}%: ratio "
              f"{c['stress ratio'][-1]:.3f}, e = {c['void ratio'][-1]:.4f}, "
              f"<a1 a1> {c['axis orientation 11'][0]:.3f} -> {c['axis orientation 11'][-1]:.3f}")
    titles = ["(a) stress ratio (s11 - s33)/p", "(c) volumetric strain (compression < 0)", "void ratio e",
              "mean axis orientation <a1 a1> (1/3 isotropic)"]
    for ax, title in zip(axes.flat, titles):
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("-eps11 (%)")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}_stress_strain.png", dpi=120)
    with open(f"{prefix}_stress_strain.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["shape", "minus_strain_11", "stress_ratio_s11_s33_over_p", "volumetric_strain", "void_ratio",
                         "axis_orientation_11"])
        writer.writerows(rows)


# --- the paper's signatures, measured ------------------------------------------------------------

BIN = 0.0025
PAPER_PEAK_STRAIN = (0.02, 0.10)
PAPER_LARGE_STRAIN_RATIO = (0.8, 1.3)
REPORTED = [0.05, 0.10, 0.20, 0.60]


def bin_mean(strain, values, end):
    """Mean of values over the BIN of strain ending at `end` (NaN when no row lies there)."""
    inside = (strain > end - BIN) & (strain <= end + 1e-12)
    return float(values[inside].mean()) if inside.any() else float("nan")


def signatures(history, aspect=None):
    """The signature numbers of one history ({column: array}); strains as fractions."""
    strain = -history["strain_11"]
    ratio = (history["stress_33"] - history["stress_11"]) / history["p"]
    eps_v = history["volumetric_strain"]
    ends = np.arange(BIN, strain[-1] + 1e-9, BIN)
    means = np.array([bin_mean(strain, ratio, end) for end in ends])
    k = int(np.nanargmax(means))
    final = float(ends[-1])
    row = {"final_strain": final, "peak": float(means[k]), "peak_strain": float(ends[k]),
           "final_ratio": float(means[-1]), "softening": float(means[k] - means[-1])}
    for s in REPORTED:
        if s <= final + 1e-9:
            row[f"ratio_{100 * s:g}pc"] = bin_mean(strain, ratio, s)
            row[f"eps_v_{100 * s:g}pc"] = bin_mean(strain, eps_v, s)
    j = int(np.argmin(eps_v))
    row["min_eps_v"], row["min_eps_v_strain"] = float(eps_v[j]), float(strain[j]) + 0.0  # no -0
    # Dilation after 5%: eps_v at the end minus eps_v at 5% (the paper: all shapes dilate after 5%).
    row["dilation_after_5pc"] = float(bin_mean(strain, eps_v, final) - bin_mean(strain, eps_v, 0.05))
    # The cell: x3 (the free lateral axis) over its original width, and x1/x3 from the initial L1/L3.
    x3 = 1.0 + float(history["strain_33"][-1])
    x1 = 1.0 + float(history["strain_11"][-1])
    row["x3_growth"] = x3
    row["x1_over_x3"] = aspect * x1 / x3 if aspect else float("nan")
    row["void_ratio_final"] = float(history["void_ratio"][-1])
    row["peak_in_paper_range"] = PAPER_PEAK_STRAIN[0] <= row["peak_strain"] <= PAPER_PEAK_STRAIN[1]
    row["final_ratio_in_paper_range"] = PAPER_LARGE_STRAIN_RATIO[0] <= row["final_ratio"] <= PAPER_LARGE_STRAIN_RATIO[1]
    return row


def percent(value, digits=2, sign=True):
    return "" if np.isnan(value) else f"{100 * value:{'+' if sign else ''}.{digits}f}%"


def markdown(rows):
    lines = ["| shape | peak (strain) | ratio 10% | 20% | 60% | softening after the peak | eps_v 5% | 10% | 20% | "
             "60% | least eps_v (strain) | x3 growth | x1/x3 | e at the end |",
             "|" + " --- |" * 14]
    for label, r in rows:
        def at(key, fmt):
            return fmt(r[key]) if key in r else ""
        x1_x3 = "" if np.isnan(r["x1_over_x3"]) else f"{r['x1_over_x3']:.3f}"
        lines.append(
            f"| {label} | {r['peak']:.3f} ({percent(r['peak_strain'], 2, False)}) | {at('ratio_10pc', '{:.3f}'.format)} | "
            f"{at('ratio_20pc', '{:.3f}'.format)} | {at('ratio_60pc', '{:.3f}'.format)} | {r['softening']:.3f} | "
            f"{at('eps_v_5pc', percent)} | {at('eps_v_10pc', percent)} | {at('eps_v_20pc', percent)} | "
            f"{at('eps_v_60pc', percent)} | {percent(r['min_eps_v'])} ({percent(r['min_eps_v_strain'], 1, False)}) | "
            f"{r['x3_growth']:.3f} | {x1_x3} | "
            f"{r['void_ratio_final']:.4f} |")
    lines.append("| the paper | at 2-10%, then softening | | | 0.8-1.3 (all four) | > 0 | | | | all dilate after 5%; "
                 "alpha 0.625: +6.8% | | alpha 0.625: 2.67 | alpha 0.625: 0.22 | alpha 0.625 the smallest |")
    return "\n".join(lines)


def parse(argument):
    if "=" not in argument:
        sys.exit(f"stress_strain.py: '{argument}' is not LABEL=HISTORY[@ASPECT]\n{__doc__}")
    label, path = argument.rsplit("=", 1)
    aspect = None
    if "@" in path:
        path, text = path.rsplit("@", 1)
        try:
            aspect = float(text)
        except ValueError:
            sys.exit(f"stress_strain.py: '{argument}': the initial L1/L3 '{text}' is not a number")
    return label, path, aspect


def signatures_table(argv):
    out_csv = None
    if len(argv) >= 2 and argv[0] == "--csv":
        out_csv, argv = argv[1], argv[2:]
    if not argv:
        sys.exit(__doc__)
    rows = [(label, signatures(read_history(path), aspect)) for label, path, aspect in map(parse, argv)]
    print(markdown(rows))
    if out_csv:
        keys = list(dict.fromkeys(k for _, r in rows for k in r))
        with open(out_csv, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["shape"] + keys)
            for label, r in rows:
                writer.writerow([label] + [r.get(k, "") for k in keys])


# --- several realisations: their spread -----------------------------------------------------------

ERROR_BAR_EVERY = 0.025
SUMMARISED = [("peak", "peak", "{:.3f}"), ("peak_strain", "strain at the peak", "{:.2%}"),
              ("final_ratio", "ratio at the end", "{:.3f}"), ("softening", "softening", "{:.3f}"),
              ("eps_v_60pc", "eps_v at 60%", "{:+.2%}"), ("x3_growth", "x3 growth", "{:.3f}"),
              ("void_ratio_final", "e at the end", "{:.4f}")]


def group_of(label):
    match = re.fullmatch(r"(.*) \(realisation \d+\)", label)
    return match.group(1) if match else label


def binned_curves(history):
    strain = -history["strain_11"]
    ratio = (history["stress_33"] - history["stress_11"]) / history["p"]
    ends = np.arange(BIN, strain[-1] + 1e-9, BIN)
    return ends, np.array([bin_mean(strain, ratio, e) for e in ends]), \
        np.array([bin_mean(strain, history["volumetric_strain"], e) for e in ends])


def spread(values, fmt):
    values = np.asarray(values, dtype=float)
    if values.size == 1:
        return fmt.format(values[0])
    return f"{fmt.format(values.mean())} +- {fmt.format(values.std(ddof=1))} " \
           f"({fmt.format(values.min())} - {fmt.format(values.max())})"


def spread_figure(arguments):
    if len(arguments) < 2:
        sys.exit(__doc__)
    prefix, arguments = arguments[0], arguments[1:]
    groups = {}
    for label, path, aspect in map(parse, arguments):
        history = read_history(path)
        groups.setdefault(group_of(label), []).append((binned_curves(history), signatures(history, aspect)))
    figure, (ax_ratio, ax_volume) = plt.subplots(1, 2, figsize=(12, 4.5))
    columns, table = {}, ["| shape | realisations | " + " | ".join(t for _, t, _ in SUMMARISED) + " |",
                          "|" + " --- |" * (2 + len(SUMMARISED))]
    for k, (shape, members) in enumerate(groups.items()):
        n = min(len(c[0]) for c, _ in members)
        strain = members[0][0][0][:n]
        ratio = np.array([c[1][:n] for c, _ in members])
        volume = np.array([c[2][:n] for c, _ in members])
        columns["strain"] = strain if "strain" not in columns or len(strain) < len(columns["strain"]) \
            else columns["strain"]
        every = max(1, int(round(ERROR_BAR_EVERY / BIN)))
        for ax, values in ((ax_ratio, ratio), (ax_volume, 100 * volume)):
            mean = values.mean(axis=0)
            deviation = values.std(axis=0, ddof=1) if len(members) > 1 else np.zeros_like(mean)
            line, = ax.plot(100 * strain, mean, color=f"C{k}", label=f"{shape} ({len(members)})")
            ax.errorbar(100 * strain[every - 1::every], mean[every - 1::every], yerr=deviation[every - 1::every],
                        fmt="none", ecolor=line.get_color(), capsize=2, lw=0.8)
        columns[f"{shape}: ratio mean"] = ratio.mean(axis=0)
        columns[f"{shape}: ratio std"] = ratio.std(axis=0, ddof=1) if len(members) > 1 else 0 * strain
        columns[f"{shape}: eps_v mean"] = volume.mean(axis=0)
        columns[f"{shape}: eps_v std"] = volume.std(axis=0, ddof=1) if len(members) > 1 else 0 * strain
        values = [[s[key] for _, s in members if key in s] for key, _, _ in SUMMARISED]
        cells = [spread(v, fmt) if v else "" for v, (_, _, fmt) in zip(values, SUMMARISED)]
        table.append(f"| {shape} | {len(members)} | " + " | ".join(cells) + " |")
    ax_ratio.set_ylabel(r"$(\sigma_{11} - \sigma_{33})/p$")
    ax_volume.set_ylabel(r"volumetric strain (%), dilation +")
    for ax, title in ((ax_ratio, "(a) stress ratio"), (ax_volume, "(c) volume change")):
        ax.set_xlabel(r"strain $-\varepsilon_{11}$ (%)")
        ax.set_title(f"{title}: mean of the realisations, bars one standard deviation")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(f"{prefix}.png", dpi=150)
    n = len(columns["strain"])
    with open(f"{prefix}.csv", "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(columns)
        writer.writerows(zip(*(np.asarray(v)[:n] for v in columns.values())))
    print("\n".join(table))


if __name__ == "__main__":
    dispatch({"run": run_figure, "fig3": fig3, "shapes": shapes, "signatures": signatures_table,
              "spread": spread_figure}, __doc__, sys.argv[1:])
