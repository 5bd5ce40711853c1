#!/usr/bin/python3
"""Draw PNG figures from a lagremap run directory.

Usage:
    scripts/plot.py DIR [--out OUTDIR] [--compare LAGRANGE_DIR | --no-compare]
                        [--show-list]

DIR is a lagremap output directory.  It must hold ``summary.json``; every
other input (history.csv, the problems' CSVs, radial.csv, slice_z.csv, the
HDF5 snapshots listed in fields.xmf) is optional, and a plot whose input is
missing is skipped silently, so the script works on partial runs, quick runs
with output switched off, and directories copied around without their large
files.

Overlays, as the paper's figures: the curves of a remap run and of the
lagrange run of the same problem share one figure, lagrange solid and remap
dashed (wilkins profiles, pile wall stress, taylor length and outline, shell
radii; the beam's tip: lagrange curve, remap points).  The lagrange run is
``--compare``'s, or for a remap run in DIR a sibling directory DIR_lagrange
(what scripts/run.sh writes) or PROBLEM_lagrange when one exists; without
one the overlays show DIR's run alone, with a note.  With both runs,
comparison.md in the output directory puts their checks side by side.
Field maps (density, pressure) of 2D and multi-material runs draw the
alpha = 0.5 contour of each solid material from the snapshots.

For every PNG written the script prints its path, one per line, on stdout,
so callers (CI, the regression scripts) can collect the figures without
knowing which ones a given problem produces; notes (an optional input or
run missing) go to stderr.  ``--show-list`` prints the plots this directory
supports instead of drawing them.

Exit status: 0 on success; 1 if some input file was present but could not be
plotted (a warning names it on stderr, the other plots are still drawn);
2 if DIR does not exist or holds no readable summary.json.

All quantities are taken to be SI, because that is what the C++ code writes.

The code is the package lagremap_plot beside this script (its __init__
lists the modules); this file parses the arguments and draws the plots
lagremap_plot.registry gives the run.
"""

import argparse
import os
import sys
from typing import List, Optional

# The package lives beside this script: importable from any working directory,
# and when the script is loaded as a module (tests/test_plot.py).
HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

from lagremap_plot.comparison import write_comparison  # noqa: E402
from lagremap_plot.errors import EXIT_PLOT_FAILED, InputError, SkipPlot, fail, note  # noqa: E402
from lagremap_plot.fields import draw_alpha_contour  # noqa: E402
from lagremap_plot.pairing import find_partner  # noqa: E402
from lagremap_plot.readers import load_run, read_run  # noqa: E402
from lagremap_plot.registry import plots_for  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402  (after lagremap_plot, which selects Agg)

# What callers that load this file as a module use (tests/test_plot.py).
__all__ = ["main", "read_run", "draw_alpha_contour", "plt"]


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        description="Draw PNG figures from a lagremap output directory; "
                    "prints the path of each PNG written.")
    parser.add_argument("dir", metavar="DIR", help="lagremap output directory")
    parser.add_argument("--out", metavar="OUTDIR",
                        help="write PNGs here instead of DIR (created if needed)")
    parser.add_argument("--compare", metavar="LAGRANGE_DIR",
                        help="a run of the same problem (normally in lagrange mode) to "
                             "overlay: lagrange solid, remap dashed.  Default for a remap "
                             "run: DIR_lagrange or PROBLEM_lagrange next to DIR, if present")
    parser.add_argument("--also", metavar="DIR", action="append", default=[],
                        help="another run of the same problem to overlay too (repeatable), "
                             "e.g. the other mixed-cell closure of a remap run")
    parser.add_argument("--no-compare", action="store_true",
                        help="draw DIR's run alone (no search for a lagrange run)")
    parser.add_argument("--show-list", action="store_true",
                        help="list the plots for DIR (output, input, whether "
                             "the input is present) and draw nothing")
    args = parser.parse_args(argv)

    run = load_run(args.dir)
    out_dir = args.out or args.dir
    candidates = plots_for(run)

    if args.show_list:
        for plot in candidates:
            state = ("not-applicable" if not plot.applies(run)
                     else "available" if run.has(plot.source) else "missing-input")
            print(f"{os.path.join(out_dir, plot.output)}\t{plot.source}\t{state}")
        return 0

    if not args.no_compare:
        run.partner = find_partner(run, args.compare, auto=True)
    for extra in args.also:
        other = read_run(extra)
        if other.problem != run.problem:
            fail(f"--also: {extra} is a '{other.problem}' run, not '{run.problem}'")
        run.extras.append(other)
    todo = [p for p in candidates if run.has(p.source) and p.applies(run)]
    if todo:
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as exc:
            fail(f"{out_dir}: cannot create output directory: {exc.strerror}")

    status = 0
    for plot in todo:
        try:
            written = plot.draw(run, os.path.join(out_dir, plot.output))
        except SkipPlot as exc:
            plt.close("all")
            note(f"{plot.output} skipped: {exc}")
            continue
        except (InputError, OSError, ValueError) as exc:
            plt.close("all")
            print(f"plot.py: warning: {plot.output} skipped: {exc}",
                  file=sys.stderr)
            status = EXIT_PLOT_FAILED
            continue
        if written:
            print(written, flush=True)
    if run.partner is not None:
        try:
            table = write_comparison(run, out_dir)
        except OSError as exc:
            print(f"plot.py: warning: comparison.md not written: {exc}", file=sys.stderr)
            status = EXIT_PLOT_FAILED
        else:
            if table:
                note(f"checks of both runs side by side: {table}")
    return status


if __name__ == "__main__":
    sys.exit(main())
