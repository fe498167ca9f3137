"""Shared by the loading-convergence studies (chart_dem_rate.py, chart_dem_increment.py, the time-step
studies): the differences between two runs' stress-strain paths (the runs: runner.cached_load)."""
import numpy as np

# Where the curves are compared: past the elastic start, to the end of the run.
COMPARE_FROM = 0.005


def curves(h):
    """Axial strain (compression positive), q/p, volumetric strain (dilation positive)."""
    return -h["strain_11"], h["q"] / h["p"], h["volumetric_strain"]


def compare(h, reference, final_strain=None):
    """Differences from the reference run over COMPARE_FROM .. final strain: of mean q/p (relative), of q/p
    averaged over 1% strain bins (largest relative), and of the volumetric strain (largest absolute).
    One 1000-sphere trajectory fluctuates by about 5% in q/p from point to point, so q/p is compared in means."""
    strain, q_over_p, volumetric = curves(h)
    r_strain, r_q, r_v = curves(reference)
    end = min(strain[-1], r_strain[-1]) if final_strain is None else final_strain
    keep = (strain >= COMPARE_FROM) & (strain <= end)
    r_keep = (r_strain >= COMPARE_FROM) & (r_strain <= end)
    mean_difference = abs(q_over_p[keep].mean() - r_q[r_keep].mean()) / r_q[r_keep].mean()
    edges = np.arange(COMPARE_FROM, end + 1e-12, 0.01)
    worst_bin = 0.0
    for low, high in zip(edges[:-1], edges[1:]):
        mine = q_over_p[(strain >= low) & (strain < high)].mean()
        theirs = r_q[(r_strain >= low) & (r_strain < high)].mean()
        worst_bin = max(worst_bin, abs(mine - theirs) / theirs)
    dv = np.interp(r_strain[r_keep], strain, volumetric) - r_v[r_keep]
    return float(mean_difference), float(worst_bin), float(np.max(np.abs(dv)))


def label_curve_axes(axes):
    """Labels the stress-ratio (axes[0]) and volume (axes[1]) panels of a convergence chart and grids all."""
    axes[0].set_ylabel(r"$(\sigma_{11}-\sigma_{33})/p$")
    axes[1].set_ylabel(r"volumetric strain $\varepsilon_v$ (%), dilation positive")
    for ax in axes[:2]:
        ax.set_xlabel(r"axial strain $-\varepsilon_{11}$ (%)")
        ax.legend(fontsize=7)
    for ax in axes:
        ax.grid(alpha=0.3)
