"""One reader per file type of the stages (docs/formats/), shared by every figure script here and
every study in workflows/studies. Each returns plain numpy arrays and scalars keyed by the names
the format documents, whichever of a stage's twin files (HDF5 or CSV) it is given."""
import csv
import os

import h5py
import numpy as np

AXES = (1, 2, 3)
# The void distributions of a voids file: the ball opening, the spar along and the disk about each axis.
VOID_CURVES = ["ball"] + [f"{kind}_x{a}" for kind in ("spar", "disk") for a in AXES]


def stem(path):
    """load_007 of .../probe_load_007.csv's source column or of .../load_007.h5."""
    return os.path.splitext(os.path.basename(path))[0]


def read_table(path):
    """A CSV with a header line as {column: array}: numeric columns as float arrays, the others as lists
    of strings. None when the file is missing or has no rows."""
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    columns = {}
    for key in rows[0]:
        values = [r[key] for r in rows]
        try:
            columns[key] = np.array([float(v) for v in values])
        except ValueError:
            columns[key] = values
    return columns


def read_history(path):
    """{column: array} of a loading history, history.h5 or its history.csv twin (docs/formats/history.md;
    the CSV is the committed form of the paper-size runs)."""
    if path.endswith(".csv"):
        table = np.genfromtxt(path, delimiter=",", names=True)
        return {name: np.asarray(table[name]) for name in table.dtype.names}
    with h5py.File(path, "r") as f:
        group = f["history"]
        return {name: np.asarray(group[name][()]) for name in group}


def read_checkpoint_cell(path):
    """(lengths, reference lengths) of a DEM checkpoint's cell (docs/formats/checkpoint.md)."""
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path} is missing: the cell (and the strain) comes from the checkpoint")
    with h5py.File(path, "r") as f:
        return f["cell/lengths"][()], f["cell/reference_lengths"][()]


def checkpoint_particle_count(path):
    """Particles of a DEM checkpoint (the length of /particles/diameter)."""
    with h5py.File(path, "r") as f:
        return int(f["particles/diameter"].shape[0])


def checkpoint_strain(path):
    """Engineering strain eps_11 of a checkpoint: its cell length over the reference, minus 1."""
    lengths, reference = read_checkpoint_cell(path)
    return float(lengths[0] / reference[0] - 1.0)


def read_fabric_series(path):
    """{column: array} of `aniso-fabric series` (fabric_series.h5's /series or fabric_series.csv; 'source'
    as a list of file names), plus 'correlations' {measure: attributes} from the HDF5 file."""
    if path.endswith(".csv"):
        if not os.path.exists(path):
            raise FileNotFoundError(f"{path} is missing")
        return read_table(path)
    with h5py.File(path, "r") as f:
        out = {name: d[()] for name, d in f["series"].items()}
        out["correlations"] = {name: dict(g.attrs) for name, g in f["correlations"].items()}
        out["source_hash"] = {g.attrs["source_hash"]: -float(g.attrs["strain_11"]) for g in f["checkpoints"].values()}
    return out


def read_correlations(path, against="stress"):
    """{measure: (c1, c2)} of fabric_series_correlations.csv's rows against one quantity."""
    with open(path) as f:
        return {row["measure"]: (float(row["c1"]), float(row["c2"]))
                for row in csv.DictReader(f) if row["against"] == against}


def read_probe(path):
    """A probe result (docs/formats/probe.md) as {name: value}: from probe_<stem>.h5 the whole /stiffness
    group with its attributes and the checks' worst values; from probe_<stem>.csv the row's scalars and
    the tensors C, D, Q_plus, Q_minus as 3x3 arrays. Both give strain, K_C, C, checks_passed, source."""
    if path.endswith(".csv"):
        with open(path) as f:
            row = next(csv.DictReader(f))
        out = {key: (value if key in ("source", "source_hash") else float(value))
               for key, value in row.items() if not any(key.startswith(t + "_") for t in ("C", "D", "Q_plus", "Q_minus"))}
        for tensor in ("C", "D", "Q_plus", "Q_minus"):
            if f"{tensor}_11" in row:
                out[tensor] = np.array([[float(row[f"{tensor}_{i}{j}"]) for j in AXES] for i in AXES])
        out["checks_passed"] = int(out.get("checks_passed", 1))
        return out
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


def read_voids(path):
    """A voxel stage result, voids_<stem>.h5 (docs/formats/voids.md): L_v, R_v, porosity, the medians
    (in metres), d50, source_hash, the image's voxel count and 'curves' {distribution: (sizes in d50,
    fraction kept)}."""
    with h5py.File(path, "r") as f:
        g = f["voids"]
        out = {name: g[name][()] for name in ("L_v", "R_v", "porosity", "free_path_median", "breadth_median",
                                              "void_size_median")}
        out["curves"] = {name: (g[name]["length_d50" if name.startswith("spar") else "radius_d50"][()],
                                g[name]["fraction"][()]) for name in VOID_CURVES}
        out["d50"] = float(g.attrs["d50"])
        out["source_hash"] = g.attrs.get("source_hash")
        out["voxels"] = int(np.prod(g["shape"][()])) if "shape" in g else None
    return out


def is_collected_permeability(path):
    """True for a collected LBM result, False for the per-direction files a job array leaves beside it."""
    return "_direction" not in os.path.basename(path)


def read_permeability(path):
    """An LBM result (docs/formats/permeability.md): a collected permeability_<stem>.h5 (/permeability)
    or one flow direction's permeability_<stem>_direction<D>.h5 (/direction), as its datasets (K and
    K_lattice where written) and attributes (symmetry_error, porosity, tau, body_force, source_hash, ...),
    with 'runs' {axis, steps, seconds, reynolds, mean_momentum, throat_width, ...} of its flow runs."""
    with h5py.File(path, "r") as f:
        g = f["permeability"] if "permeability" in f else f["direction"]
        out = {name: item[()] for name, item in g.items() if isinstance(item, h5py.Dataset)}
        out.update({key: value.decode() if isinstance(value, bytes) else value for key, value in g.attrs.items()})
        out["runs"] = {name: d[()] for name, d in g["runs"].items()}
    return out
