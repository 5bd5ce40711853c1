#!/usr/bin/python3
"""Compare a remap run's final pressure with a lagrange run's, as the paper's
figures do by eye (docs/verification.md, "Remap against Lagrange fields").

usage: scripts/compare_fields.py REMAP_DIR LAGRANGE_DIR [--material K]

Samples the lagrange run's last snapshot at the centres of the remap mesh's
cells (the lagrange cell with the nearest centroid: the Lagrangian cells are
of the remap cells' size) and prints the mean and the 95th percentile of
|p_remap - p_lagrange| / max |p_lagrange| over the body's cells (alpha^K >=
1/2) and over its interface cells (0.05 <= alpha^K < 1/2). The remap pressure
is the cell's mixture pressure; a remap cell centre outside the deformed
lagrange body (farther from every lagrange centroid than a lagrange cell's
reach) is left out and counted.
"""
import argparse
import glob
import sys

import h5py
import numpy as np


def last_snapshot(folder):
    files = sorted(glob.glob(folder + "/fields_*.h5"))
    if not files:
        sys.exit(f"compare_fields: no fields_*.h5 in {folder}")
    return h5py.File(files[-1], "r")


def cell_centres(snapshot):
    xyz = snapshot["mesh/coordinates"][()]
    cells = snapshot["mesh/connectivity"][()].reshape(-1, 8)
    return xyz[cells].mean(axis=1), xyz[cells]


def nearest(points, targets, chunk=2048):
    """Index of the nearest target for every point, and its distance."""
    index = np.empty(len(points), dtype=np.int64)
    distance = np.empty(len(points))
    for start in range(0, len(points), chunk):
        block = points[start:start + chunk]
        d2 = ((block[:, None, :] - targets[None, :, :]) ** 2).sum(axis=2)
        index[start:start + chunk] = d2.argmin(axis=1)
        distance[start:start + chunk] = np.sqrt(d2.min(axis=1))
    return index, distance


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("remap_dir")
    parser.add_argument("lagrange_dir")
    parser.add_argument("--material", type=int, default=0, help="the body's material index")
    args = parser.parse_args()
    remap, lagrange = last_snapshot(args.remap_dir), last_snapshot(args.lagrange_dir)
    alpha = remap[f"fields/volume_fraction_{args.material}"][()]
    p_remap = remap["fields/pressure"][()]
    p_lagrange = lagrange["fields/pressure"][()]
    centres, _ = cell_centres(remap)
    lag_centres, lag_nodes = cell_centres(lagrange)
    reach = np.sqrt(((lag_nodes - lag_centres[:, None, :]) ** 2).sum(axis=2)).max()
    scale = np.abs(p_lagrange).max()
    print(f"remap {args.remap_dir} (t = {remap.attrs.get('time', float('nan'))}) against "
          f"lagrange {args.lagrange_dir}; max |p_lagrange| = {scale:.4g} Pa")
    for name, chosen in (("body", alpha >= 0.5), ("interface", (alpha >= 0.05) & (alpha < 0.5))):
        index, distance = nearest(centres[chosen], lag_centres)
        inside = distance <= reach
        error = np.abs(p_remap[chosen][inside] - p_lagrange[index[inside]]) / scale
        if error.size == 0:
            print(f"{name:9s}: no cells")
            continue
        print(f"{name:9s}: {error.size:6d} cells ({(~inside).sum()} outside the lagrange body), "
              f"mean {error.mean():.4f}, 95th percentile {np.percentile(error, 95):.4f}")


if __name__ == "__main__":
    main()
