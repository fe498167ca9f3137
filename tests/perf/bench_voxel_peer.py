#!/usr/bin/python3
"""The route a user would otherwise take: scipy.ndimage (and scikit-image, if installed) binary
openings, one per size, for the ball, the three disks and the three spars, on a voxel image
written by bench_voxel --image (or aniso-voxel). Periodicity by wrap padding: the image is padded
by the element's extent (the reach of an erosion then a dilation) and cropped back, which makes the opening
exactly the periodic one. Every kept-voxel count is compared with aniso's voids_<stem>.h5 (same
sizes), so the peer also cross-checks our results, and the time is compared with aniso's.

usage: bench_voxel_peer.py IMAGE.h5 VOIDS.h5 [--skimage] [--max-seconds S]
"""
import sys
import time

import h5py
import numpy as np
from scipy import ndimage


def element(kind, axis, size):
    """Structuring element as a boolean array (axes in the image's [x3, x2, x1] order)."""
    if kind == "spar":
        shape = [1, 1, 1]
        shape[2 - axis] = int(size)
        return np.ones(shape, dtype=bool)
    r = int(np.floor(size))
    r2 = int(np.floor(size * size + 1e-9))
    z, y, x = np.mgrid[-r:r + 1, -r:r + 1, -r:r + 1]
    ball = x * x + y * y + z * z <= r2
    if kind == "ball":
        return ball
    keep = [x, y, z][axis] == 0  # disk with axis x_{axis+1}: offsets with zero component along it
    return ball & keep


def periodic_opening(void, structure, opening):
    # Erosion then dilation reach at most 2 * (s // 2) <= s voxels from a voxel along an axis
    # where the element spans s voxels (centred origin): pad by s, open, crop.
    pad = [(s, s) for s in structure.shape]
    padded = np.pad(void, pad, mode="wrap")
    opened = opening(padded, structure)
    crop = tuple(slice(s, s + n) for s, n in zip(structure.shape, void.shape))
    return opened[crop]


def main():
    image_path, voids_path = sys.argv[1], sys.argv[2]
    use_skimage = "--skimage" in sys.argv
    max_seconds = float(sys.argv[sys.argv.index("--max-seconds") + 1]) if "--max-seconds" in sys.argv else 1e9
    with h5py.File(image_path, "r") as f:
        void = f["image/phase"][...] == 0
    with h5py.File(voids_path, "r") as f:
        curves = []
        for kind, group in [("ball", "ball")] + [(k, f"{k}_x{a + 1}") for k in ("disk", "spar") for a in range(3)]:
            g = f["voids"][group]
            size = g["length" if kind == "spar" else "radius"][...]
            kept = g["kept"][...]
            axis = int(group[-1]) - 1 if kind != "ball" else 0
            # Spar sizes beyond the longest run keep nothing (or only all-void lines): stop there.
            last = len(size) if kind != "spar" else int(np.nonzero(kept > kept[-1])[0].max()) + 2
            curves.append((kind, axis, size[1:last], kept[1:last]))
    openings = [("scipy.ndimage.binary_opening",
                 lambda a, s: ndimage.binary_opening(a, structure=s))]
    if use_skimage:
        from skimage import morphology
        openings.append(("skimage.morphology.binary_opening",
                         lambda a, s: morphology.binary_opening(a, footprint=s)))
    print(f"image {image_path}: {void.shape[::-1]} (x1, x2, x3) = {void.size} voxels")
    for name, opening in openings:
        start = time.perf_counter()
        cpu_start = time.process_time()
        done = mismatches = 0
        for kind, axis, sizes, kept in curves:
            for size, expected in zip(sizes, kept):
                if time.perf_counter() - start > max_seconds:
                    break
                count = int(periodic_opening(void, element(kind, axis, size), opening).sum())
                done += 1
                print(f"  {kind} axis {axis + 1} size {size:g}: {count} kept", flush=True)
                if count != int(expected):
                    mismatches += 1
                    print(f"  MISMATCH {kind} axis {axis + 1} size {size}: {name} {count}, aniso {expected}")
        seconds = time.perf_counter() - start
        cpu = time.process_time() - cpu_start
        total = sum(len(c[2]) for c in curves)
        print(f"{name}: {done} of {total} openings in {seconds:.2f} s wall, {cpu:.2f} s CPU "
              f"({cpu / max(done, 1):.3f} CPU s each), {mismatches} mismatches with aniso", flush=True)


if __name__ == "__main__":
    main()
