"""Strong-scaling table and plot from perf/strong_scaling.sh's results.csv.

Usage: /usr/bin/python3 perf/plot_scaling.py RESULTS.csv OUT.png
Prints a markdown table (best run of each configuration: cell-steps per
second, speed-up and parallel efficiency against 1 rank x 1 thread, halo
share of the wall time) and draws speed-up against cores, ranks and threads
told apart, with the ideal line.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    best = {}
    for row in rows:
        fom = float(row["cell_steps_per_second"])
        if row["config"] not in best or fom > float(best[row["config"]]["cell_steps_per_second"]):
            best[row["config"]] = row
    base = float(best["1x1"]["cell_steps_per_second"]) if "1x1" in best else None
    print("| ranks x threads | cores | cell-steps/s | speed-up | efficiency | halo share |")
    print("|---|---|---|---|---|---|")
    points = []
    for config, row in best.items():
        ranks, threads = int(row["ranks"]), int(row["threads"])
        cores = ranks * threads
        fom = float(row["cell_steps_per_second"])
        speedup = fom / base if base else float("nan")
        halo = float(row["halo_seconds"]) / float(row["wall_seconds"])
        print(f"| {ranks} x {threads} | {cores} | {fom:.4g} | {speedup:.2f} | {speedup / cores:.0%} | {halo:.1%} |")
        points.append((cores, speedup, ranks, threads))
    fig, ax = plt.subplots(figsize=(5, 4))
    top = max(p[0] for p in points)
    ax.plot([1, top], [1, top], "k:", label="ideal")
    for label, pick, marker in (("threads (1 rank)", lambda p: p[2] == 1, "o-"),
                                ("ranks (1 thread each)", lambda p: p[3] == 1, "s--")):
        chosen = sorted(p for p in points if pick(p))
        if chosen:
            ax.plot([p[0] for p in chosen], [p[1] for p in chosen], marker, label=label)
    ax.set_xlabel("cores (ranks x threads)")
    ax.set_ylabel("speed-up over 1 x 1 (cell-steps/s)")
    ax.set_title("lagremap strong scaling")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
