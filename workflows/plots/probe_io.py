"""Reading aniso-probe results (probe_<stem>.h5, docs/formats/probe.md) for the probe charts."""
import h5py
import numpy as np


def read_probe(path):
    """The /stiffness group of a probe result as a dict of numpy arrays and scalars."""
    with h5py.File(path, "r") as f:
        g = f["stiffness"]
        out = {name: g[name][...] for name in g}
        for name in ("K_C", "strain", "increment", "inertial_number", "hold_steps", "window_steps",
                     "checks_passed", "source", "source_hash"):
            out[name] = g.attrs[name]
        forks = f["forks"]
        out["steps_per_fork"] = 2 * (int(forks["fork_1"].attrs["half_steps"]) + int(forks["fork_1"].attrs["hold_steps"]))
    out["linearity"] = max(out["linearity_plus"].max(), out["linearity_minus"].max())
    out["noise"] = max(out["noise_plus"].max(), out["noise_minus"].max())
    out["sliding"] = max(out["sliding_plus"].max(), out["sliding_minus"].max())
    out["resolution"] = min(out["resolution_plus"].min(), out["resolution_minus"].min())
    return out


def relative_error(C, reference):
    """Frobenius norm of C - reference relative to the reference's."""
    return float(np.linalg.norm(C - reference) / np.linalg.norm(reference))
