"""Reading aniso history files (docs/formats/history.md) for the plotting scripts."""
import h5py
import numpy as np


def read_history(path):
    """Returns {column name: numpy array} from a history.h5 file or its history.csv twin (the
    committed form of the paper-size runs, docs/paper-size/)."""
    if path.endswith(".csv"):
        table = np.genfromtxt(path, delimiter=",", names=True)
        return {name: np.asarray(table[name]) for name in table.dtype.names}
    with h5py.File(path, "r") as f:
        group = f["history"]
        return {name: np.asarray(group[name][()]) for name in group}
