"""Reading aniso history files (docs/formats/history.md) for the plotting scripts."""
import h5py
import numpy as np


def read_history(path):
    """Returns {column name: numpy array} from a history.h5 file."""
    with h5py.File(path, "r") as f:
        group = f["history"]
        return {name: np.asarray(group[name][()]) for name in group}
