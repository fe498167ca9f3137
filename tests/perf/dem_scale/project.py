#!/usr/bin/python3
"""Weak-scaling projection of aniso-dem from the scale benchmark (issue 47, item 4).

usage: project.py RESULTS.csv PREPARED.h5 [--ranks 2,64,1024] [--per-rank 15625,480000]
                  [--latency-us 2] [--allreduce-us 1.5] [--pack-gb-s G] [--partners 26]

RESULTS.csv is what tests/perf/dem_scale/run.sh wrote (particle-steps per second at each size on 1
and 2 ranks, the halo's seconds); PREPARED.h5 the assembly it tiled. A step on P ranks, each holding
N_r particles in a cube of side a, is modelled as

    t(P) = t_c(N_r) (1 + f_force d(N_r)) + g(N_r) b / B + m alpha + c alpha_c log2 P

- t_c(N_r): one rank's step time at N_r particles, interpolated in log N between the measured sizes
  on 1 rank (the memory-bound drop from the 6400-particle figure included);
- d(N_r): the pairs a rank computes twice because one partner is a ghost, over its own pairs: the
  pairs crossing a plane per unit area (counted in PREPARED.h5) times the cube's surface 6 a^2,
  over N_r times the pairs per particle; f_force the force pass's share of a step;
- g(N_r): ghosts per rank, the number density times the shell of one bin width w around the
  cube, (a + 2 w)^3 - a^3, with w the bin width aniso's decomposition draws (at least the reach
  2 r_max + skin); b = 104 bytes a ghost state, B the pack-copy-unpack rate measured on 2 ranks
  (the halo section's time over the bytes sent, when --pack-gb-s is not given);
- m alpha: one message latency per partner rank; c alpha_c log2 P: the per-step collectives (the
  motion bound and the explosion check every step, the control sums every 4th: c = 2.25).

The efficiency is t_c(N_r) / t(P). Checked against the 2-rank measurement: the same formula with
two slabs instead of a cube (ghosts on two faces) must reproduce the measured ghosts and per-core
rate, which the script prints beside its prediction.
"""
import argparse
import collections
import csv
import math
import statistics

import h5py
import numpy as np
from scipy.spatial import cKDTree

STATE_BYTES = 13 * 8  # position, orientation, velocity, angular velocity (dem/parallel/halo.cpp)


def measured_rates(path):
    values = collections.defaultdict(list)
    for row in csv.DictReader(open(path)):
        values[(int(row["particles"]), int(row["ranks"]), row["measure"])].append(float(row["value"]))
    return values


def packing(path):
    with h5py.File(path, "r") as f:
        lengths = f["cell/lengths"][:]
        x = f["particles/position"][:] % lengths
        radius = f["particles/diameter"][:] / 2
        skin = float(f["parameters"].attrs["skin"])
        d50 = float(f["parameters"].attrs["d50"])  # of the grading by mass, the config's unit
    reach = 2 * radius.max() + skin
    tree = cKDTree(x, boxsize=lengths)
    pairs = tree.query_pairs(reach, output_type="ndarray")
    branch = x[pairs[:, 1]] - x[pairs[:, 0]]
    branch -= lengths * np.round(branch / lengths)
    candidate = np.linalg.norm(branch, axis=1) < radius[pairs[:, 0]] + radius[pairs[:, 1]] + skin
    branch = branch[candidate]
    volume = float(np.prod(lengths))
    density = len(x) / volume
    # A plane at a uniform position along axis k cuts a pair with probability |dx_k| / L_k.
    crossing_per_area = float(np.mean(np.abs(branch).sum(axis=0))) / volume
    return {"density": density, "reach": reach, "pairs_per_particle": len(branch) / len(x),
            "crossing_per_area": crossing_per_area, "d50": d50}


def one_rank_time(values, steps, n):
    """Seconds per step of one rank holding n particles, log-interpolated between measured sizes."""
    sizes = sorted(s for s, r, m in values if r == 1 and m == "hold_loop_s")
    rate = {s: s * steps / statistics.median(values[(s, 1, "hold_loop_s")]) for s in sizes}
    if n <= sizes[0]:
        per_particle = rate[sizes[0]]
    elif n >= sizes[-1]:
        per_particle = rate[sizes[-1]]
    else:
        hi = next(s for s in sizes if s >= n)
        lo = max(s for s in sizes if s <= n)
        t = 0 if hi == lo else math.log(n / lo) / math.log(hi / lo)
        per_particle = math.exp((1 - t) * math.log(rate[lo]) + t * math.log(rate[hi]))
    return n / per_particle


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results")
    parser.add_argument("prepared")
    parser.add_argument("--steps", type=int, default=200, help="steps of each hold in RESULTS")
    parser.add_argument("--ranks", default="2,64,1024")
    parser.add_argument("--per-rank", default="15625,480000")
    parser.add_argument("--latency-us", type=float, default=2.0, help="point-to-point message latency")
    parser.add_argument("--allreduce-us", type=float, default=1.5, help="latency per tree level of an allreduce")
    parser.add_argument("--pack-gb-s", type=float, default=None, help="halo bytes per second (default: measured)")
    parser.add_argument("--partners", type=int, default=26, help="neighbour ranks of a cube in a 3-D partition")
    parser.add_argument("--force-share", type=float, default=0.70, help="the force pass's share of a step")
    args = parser.parse_args()
    values = measured_rates(args.results)
    p = packing(args.prepared)
    d50 = p["d50"]
    largest = max(s for s, r, m in values if r == 2 and m == "hold_loop_s")
    # The 2-rank check: two slabs across the tiled cell's longest axis, ghosts on their two faces,
    # one bin deep (the axis cut into whole bins of at least the reach).
    with h5py.File(args.prepared, "r") as f:
        base_lengths = f["cell/lengths"][:]
        base_count = len(f["particles/diameter"])
    loop2 = statistics.median(values[(largest, 2, "hold_loop_s")]) / args.steps
    halo2 = statistics.median(values[(largest, 2, "halo_s")]) / args.steps
    tiled_long = (largest / base_count) ** (1 / 3) * base_lengths.max()
    face = largest / p["density"] / tiled_long
    width = tiled_long / math.floor(tiled_long / p["reach"])
    ghosts2 = 2 * face * width * p["density"]
    ghosts_logged = values.get((largest, 2, "ghosts_per_rank"))
    sent2 = statistics.median(ghosts_logged) if ghosts_logged else ghosts2
    pack = args.pack_gb_s * 1e9 if args.pack_gb_s else sent2 * STATE_BYTES / halo2
    t1 = one_rank_time(values, args.steps, largest / 2)
    duplicated2 = 2 * face * p["crossing_per_area"] / (largest / 2 * p["pairs_per_particle"])
    predicted2 = t1 * (1 + args.force_share * duplicated2) + ghosts2 * STATE_BYTES / pack + args.latency_us * 1e-6
    print(f"packing: {p['density'] * d50 ** 3:.3f} particles per d50^3, reach {p['reach'] / d50:.2f} d50, "
          f"bin width {width / d50:.2f} d50, {p['pairs_per_particle']:.2f} candidate pairs per particle, "
          f"{p['crossing_per_area'] * d50 ** 2:.3f} pairs crossing a plane per d50^2")
    measured_ghosts = f"{sent2:.0f}" if ghosts_logged else "not logged"
    print(f"check on 2 ranks, {largest} particles: ghosts per rank modelled {ghosts2:.0f} (measured "
          f"{measured_ghosts}); duplicated pairs {100 * duplicated2:.1f}%; halo rate {pack / 1e9:.2f} GB/s; "
          f"step {1e3 * predicted2:.1f} ms modelled, {1e3 * loop2:.1f} ms measured "
          f"(per-core rate {largest / 2 / predicted2:.3g} modelled, {largest / 2 / loop2:.3g} measured)")
    print()
    print("| particles per rank | ranks | ghosts per rank (% of owned) | pairs computed twice | "
          "compute [ms] | halo [ms] | collectives [ms] | step [ms] | weak-scaling efficiency |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for n in (int(v) for v in args.per_rank.split(",")):
        a = (n / p["density"]) ** (1 / 3)
        # Bins whole along the cube's side: the shell is one bin wide.
        w = a / max(1, math.floor(a / p["reach"]))
        ghosts = p["density"] * ((a + 2 * w) ** 3 - a ** 3)
        duplicated = 6 * a * a * p["crossing_per_area"] / (n * p["pairs_per_particle"])
        tc = one_rank_time(values, args.steps, n)
        for ranks in (int(v) for v in args.ranks.split(",")):
            if ranks == 2:
                continue
            compute = tc * (1 + args.force_share * duplicated)
            halo = ghosts * STATE_BYTES / pack + args.partners * args.latency_us * 1e-6
            collectives = 2.25 * args.allreduce_us * 1e-6 * math.log2(ranks)
            step = compute + halo + collectives
            print(f"| {n:,} | {ranks} | {ghosts:,.0f} ({100 * ghosts / n:.0f}%) | {100 * duplicated:.1f}% | "
                  f"{1e3 * compute:.2f} | {1e3 * halo:.2f} | {1e3 * collectives:.3f} | {1e3 * step:.2f} | "
                  f"{tc / step:.2f} |")


if __name__ == "__main__":
    main()
