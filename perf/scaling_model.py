#!/usr/bin/env python3
"""Weak- and strong-scaling model of lagremap on a large machine, from what
perf/weak_scaling.sh measured here (docs/performance.md, Parallel runs).

The time of a step on a rank holding an n x n x n block (N = n^3 cells) is

    T = N / R  +  m_link L_nb latency  +  bytes_face 6 (n / n_m)^2 / bandwidth
               +  K 2 ceil(log2 P) latency

- N / R: the kernels, at R cell-steps/s per rank: the measured one-core rate
  of the 1-rank run times --cores-per-rank times --node-efficiency (a rank is
  a socket; on-node threading is not modelled further);
- the halo: an interior rank exchanges with its 26 neighbours (faces, edges,
  corners; L_nb = 26), m_link messages per neighbour and step as measured on
  the 2 x 2 x 2 grid (where each rank has 7), and 6 faces of ghost data whose
  bytes are the measured per-face bytes scaled from n_m^2 to n^2 (edge and
  corner data, O(n), left out);
- the reductions: K per step (measured), each a recursive-doubling allreduce
  of 2 ceil(log2 P) latency-bound messages;
- no overlap of communication and computation, no network contention, the
  packing of the ghost data (memory copies) in N / R.

Weak scaling: N cells per rank on P ranks, efficiency T(1) / T(P), T(1)
without communication. Strong scaling: the global mesh of --strong-cells on P
ranks, efficiency T(P0) P0 / (T(P) P) against the smallest P0.

    perf/scaling_model.py out/weak_scaling/results.csv [options]
"""
import argparse
import csv
import math
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", help="results.csv of perf/weak_scaling.sh")
    parser.add_argument("--cells-per-rank", type=float, default=1e6)
    parser.add_argument("--strong-cells", type=float, default=64e6,
                        help="global cells of the strong-scaling case (default 64e6)")
    parser.add_argument("--cores-per-rank", type=float, default=32)
    parser.add_argument("--node-efficiency", type=float, default=0.8,
                        help="rate of a rank over cores-per-rank times the one-core rate")
    parser.add_argument("--bandwidth", type=float, default=25e9, help="bytes/s per rank")
    parser.add_argument("--latency", type=float, default=2e-6, help="seconds per message")
    parser.add_argument("--ranks", default="64,512,4096")
    args = parser.parse_args()

    rows = list(csv.DictReader(open(args.results)))
    one = next((r for r in rows if int(r["ranks"]) == 1), None)
    cube = next((r for r in rows if r["grid"] == "2x2x2"), None)
    if one is None or cube is None:
        sys.exit("scaling_model: results.csv needs the 1-rank and the 8-rank (2x2x2) runs")
    steps = int(one["steps"])
    core_rate = float(one["cells"]) * steps / float(one["wall_seconds"])
    rate = core_rate * args.cores_per_rank * args.node_efficiency
    n_m = round(float(cube["cells_per_rank"]) ** (1.0 / 3.0))
    bytes_face = float(cube["halo_bytes_per_step"]) / 8 / 3  # 3 cut faces per rank
    messages_link = float(cube["halo_messages_per_step"]) / 8 / 7  # 7 neighbours per rank
    reductions = float(cube["reductions_per_step"])

    def step_time(cells, ranks):
        n = cells ** (1.0 / 3.0)
        compute = cells / rate
        if ranks == 1:
            return compute, 0.0, 0.0
        halo = (26 * messages_link * args.latency +
                6 * bytes_face * (n / n_m) ** 2 / args.bandwidth)
        reduce = reductions * 2 * math.ceil(math.log2(ranks)) * args.latency
        return compute, halo, reduce

    print("Measured: one-core rate %.3g cell-steps/s (1 rank, %s cells); on %s ranks (%s^3 cells "
          "each): %.3g bytes per cut face and step, %.2f messages per neighbour and step, "
          "%.1f reductions per step." % (core_rate, one["cells"], cube["ranks"], n_m, bytes_face,
                                        messages_link, reductions))
    print("Assumed: a rank = %g cores at %.0f%% of their one-core rate (%.3g cell-steps/s), "
          "%.3g GB/s and %.3g us per message.\n" % (
              args.cores_per_rank, 100 * args.node_efficiency, rate, args.bandwidth / 1e9,
              args.latency * 1e6))
    ranks = [int(p) for p in args.ranks.split(",")]
    t1 = sum(step_time(args.cells_per_rank, 1))
    print("| ranks | weak: cells/rank | step [ms] (kernels + halo + reductions) | weak efficiency "
          "| strong: cells/rank | step [ms] | strong efficiency |")
    print("|---:|---:|---|---:|---:|---|---:|")
    p0 = ranks[0]
    strong0 = sum(step_time(args.strong_cells / p0, p0)) * p0
    for p in ranks:
        weak = step_time(args.cells_per_rank, p)
        strong = step_time(args.strong_cells / p, p)
        print("| %d | %.3g | %.2f (%.2f + %.3f + %.3f) | %.3f | %.3g | %.3f (%.3f + %.3f + %.3f) | "
              "%.3f |" % (p, args.cells_per_rank, 1e3 * sum(weak), 1e3 * weak[0], 1e3 * weak[1],
                          1e3 * weak[2], t1 / sum(weak), args.strong_cells / p,
                          1e3 * sum(strong), 1e3 * strong[0], 1e3 * strong[1], 1e3 * strong[2],
                          strong0 / (sum(strong) * p)))


if __name__ == "__main__":
    main()
