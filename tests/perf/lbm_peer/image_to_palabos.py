#!/usr/bin/python3
"""Converts an aniso voxel image (HDF5, /image/phase [n3, n2, n1], 1 = solid) to the text
geometry palabos_bench reads: n1*n2*n3 integers, x slowest and z fastest (Palabos order).
usage: image_to_palabos.py IMAGE.h5 OUT.txt   (prints "n1 n2 n3")"""
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1]) as f:
    phase = f["image/phase"][...]  # [z, y, x]
np.savetxt(sys.argv[2], phase.transpose(2, 1, 0).reshape(-1, 1), fmt="%d")
n3, n2, n1 = phase.shape
print(n1, n2, n3)
