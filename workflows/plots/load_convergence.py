"""Shared by the loading-convergence charts (chart_dem_rate.py, chart_dem_increment.py):
cached `aniso-dem load` runs and the differences between two runs' stress-strain paths."""
import os
import subprocess
import time

import numpy as np

from history_io import read_history

# Where the curves are compared: past the elastic start, to the end of the run.
COMPARE_FROM = 0.005


def finished_load(folder, final_strain):
    """(history, wall seconds) of a load in `folder` that reached `final_strain`, else None."""
    try:
        h = read_history(f"{folder}/history.h5")
        if abs(-h["strain_11"][-1] - final_strain) < 1e-3 * final_strain and os.path.exists(f"{folder}/wall.txt"):
            return h, float(open(f"{folder}/wall.txt").read())
    except (OSError, KeyError):
        pass
    return None


def cached_load(binary, prepared, folder, settings, final_strain):
    """Runs `aniso-dem load` with `settings` (key=value strings) into `folder`, to `final_strain`, unless a
    finished run is there already (so an interrupted chart continues). Returns (history, wall seconds)."""
    os.makedirs(folder, exist_ok=True)
    if (done := finished_load(folder, final_strain)) is not None:
        return done
    command = [binary, "load", "--input", prepared, "--set", f"dem.output_dir={folder}",
               "--set", f"dem.load.final_strain={final_strain}",
               "--set", f"dem.load.history_interval={final_strain / 200}"]
    for setting in settings:
        command += ["--set", setting]
    start = time.monotonic()
    with open(f"{folder}/log.txt", "w") as log:
        subprocess.run(command, check=True, stdout=log, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    with open(f"{folder}/wall.txt", "w") as out:
        out.write(f"{wall}\n")
    return read_history(f"{folder}/history.h5"), wall


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
