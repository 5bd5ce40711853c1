#!/usr/bin/python3
"""Mesh-convergence study of a lagremap problem: run it at several scales,
tabulate and plot how its answers change with the cell size.

Usage:
    scripts/convergence.py PROBLEM [--mode lagrange|remap] [--scales 0.5,1,2]
                           [--output DIR] [--lagremap EXE] [--force | --table-only]
                           [--wall] [--dim D] [--require-order NAME=MIN]...
                           [--finest-only] [-- LAGREMAP ARGUMENTS...]
    scripts/convergence.py --sweep RUN_DIR [RUN_DIR...] [--wall]

Each scale S is run as ``lagremap --problem PROBLEM [--mode M] --scale S
--output DIR/scale_S --quiet ARGUMENTS`` (``--scale`` multiplies every cell
count above one; DIR defaults to out/convergence/PROBLEM[_MODE], the binary
to build/lagremap).  A directory that already holds a finished run
(summary.json) made with the same command line is read instead of run again
(``--force`` reruns it; a finished run without the script's record of its
command line, e.g. one made by hand in pieces with --restart, is read as it
is); ``--table-only`` runs nothing and reads the runs already there.  A run
whose checks fail (lagremap's exit code 1) is still tabulated, marked; one
that fails mid-way (3) or is refused (2) stops the study with one line.

Cell size: h = cells^(-1/d), d the number of refined directions: the mesh
axes of more than one cell (mesh.nx, mesh.ny, mesh.nz of summary.json's
configuration; --scale refines only those), or --dim.  On a block of n_i
cells along its d refined axes, h is the geometric mean of the 1/n_i: the
cell length in units of the domain's extent along each axis (1/200 for
sod's 200-cell unit tube).  Only ratios of h enter the orders below, and
they follow from the cell counts actually built (a scaled count is rounded
to a whole number of cells).

Two kinds of table, chosen by what summary.json holds:

* Against an exact solution: when summary.json has ``l1_errors`` (density,
  velocity, pressure; the L1 norms of the error over the domain), or else
  the checks ``l1_density``, ``l1_velocity``, ``l1_pressure`` (sod, and the
  two-material tubes' density), each scale's errors and the observed order
  between successive scales, p = ln(e_coarse/e_fine) / ln(h_coarse/h_fine).
* Otherwise: every check's value at each scale, its change between
  successive scales and, from three scales (the finest three in the main
  table; every successive triple in a second one when there are more), the
  observed order p, Richardson's extrapolated value
  f_ext = f1 + (f1 - f2)/(r21^p - 1) and Roache's grid convergence index
  GCI_fine = 1.25 |(f2 - f1)/f1| / (r21^p - 1), where f1 is the finest
  run's value and r21 = h2/h1 > 1 (Roache 1994, 1998).  For a constant
  refinement ratio r, p = ln(|f3 - f2| / |f2 - f1|) / ln r; otherwise p
  solves the fixed-point equation of Celik et al. (2008),
  p = [ln|e32/e21| + q(p)] / ln r21,  q(p) = ln((r21^p - 1)/(r32^p - 1)).
  p is "oscillatory" when the two changes differ in sign, "n/a" when one of
  them vanishes (below 1e-12 of the value) or a value is missing, and
  "diverging" when the equation has no positive root (the changes do not
  shrink as the model f = f_ext + C h^p needs); f_ext and GCI then stay
  empty.

``--require-order NAME=MIN`` (repeatable; NAME is density, velocity or
pressure, or a check's name) exits 1 with one line when the observed order
of NAME is below MIN between any two successive scales (exact solution) or
for any successive triple (checks), or only the finest pair or triple with
``--finest-only``; a p that is not a number counts as below.

Output: the markdown table on stdout and in DIR/convergence.md; the log-log
plot DIR/convergence.png (the L1 errors, or each check's change relative to
its value |f_coarse - f_fine| / |f_fine| at the finer run's h, against h,
with slopes 1 and 2 for reference); notes and progress on stderr.

``--sweep RUN_DIR...`` runs nothing: it prints one table of every run named
(problem, mode, mesh, cells, steps, optionally wall seconds, status, then each
check's value, reference, tolerance and result), e.g. for a whole set of
runs at --scale 2.

Exit status: 0; 1 a --require-order bound is not met; 2 bad input (unknown
problem, bad scales or option, lagremap refusing its arguments, a run
missing for --table-only or --sweep); 3 a run failed mid-way or lagremap
could not be started.

References: P. J. Roache (1994), Perspective: a method for uniform
reporting of grid refinement studies, J. Fluids Eng. 116; P. J. Roache
(1998), Verification and Validation in Computational Science and
Engineering, Hermosa; I. B. Celik, U. Ghia, P. J. Roache, C. J. Freitas,
H. Coleman, P. E. Raad (2008), Procedure for estimation and reporting of
uncertainty due to discretization in CFD applications, J. Fluids Eng. 130.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

EXIT_ORDER_BELOW = 1
EXIT_BAD_INPUT = 2
EXIT_RUN_FAILED = 3

L1_FIELDS = ("density", "velocity", "pressure")
GCI_SAFETY_FACTOR = 1.25  # Roache's, for three or more grids
VANISHING_CHANGE = 1e-12  # a change below this fraction of the value is none
ROUND_OFF_CHECK = 1e-9  # a check this small at every scale (a symmetry error) is not plotted
RECORD = "convergence_run.json"  # the command line a run directory was made with
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class StudyError(Exception):
    """Stops the study with one line on stderr and the given exit status."""

    def __init__(self, message: str, status: int):
        super().__init__(message)
        self.status = status


# --------------------------------------------------------------------------
# Orders, Richardson extrapolation and the grid convergence index
# --------------------------------------------------------------------------

def pair_order(e_coarse: Optional[float], e_fine: Optional[float],
               h_coarse: float, h_fine: float) -> Optional[float]:
    """Observed order between two runs of errors e against an exact
    solution; None when an error is missing or not positive."""
    if e_coarse is None or e_fine is None or e_coarse <= 0 or e_fine <= 0:
        return None
    return math.log(e_coarse / e_fine) / math.log(h_coarse / h_fine)


def _celik_residual(p: float, log_ratio: float, r21: float, r32: float) -> float:
    """p ln r21 - ln|e32/e21| - q(p) for monotone changes (s = +1)."""
    return p * math.log(r21) - log_ratio - math.log((r21 ** p - 1.0) / (r32 ** p - 1.0))


def celik_order(e21: float, e32: float, r21: float, r32: float) -> Optional[float]:
    """Positive root p of Celik et al.'s (2008) equation for changes of one
    sign, e21 = f2 - f1 and e32 = f3 - f2 (1 the finest run), r21 = h2/h1,
    r32 = h3/h2 > 1; None when there is none.  With r21 = r32 it is
    ln(e32/e21)/ln r.  Otherwise the paper's fixed-point iteration
    p <- |ln|e32/e21| + q(p)| / ln r21, kept when it settles on a root of
    the equation without the absolute value, and bisection on that
    equation where it does not (it can take hundreds of steps, or never
    settle, when the two ratios differ much)."""
    log_ratio = math.log(abs(e32 / e21))
    if abs(r21 - r32) <= 1e-12 * r21:
        p = log_ratio / math.log(r21)
        return p if p > 0 else None
    p = log_ratio / math.log(r21)  # q = 0: the constant-ratio value
    for _ in range(1000):
        if not 0 < p < 100:
            break
        q = math.log((r21 ** p - 1.0) / (r32 ** p - 1.0))
        p_next = abs(log_ratio + q) / math.log(r21)
        if abs(p_next - p) <= 1e-12 * (1.0 + p):
            if p_next > 0 and log_ratio + q > 0:
                return p_next
            break
        p = p_next
    # Bisection: the first sign change of the residual on a grid of p.
    grid = [0.01 * 1.1 ** k for k in range(100)]  # 0.01 .. about 125
    values = [_celik_residual(p, log_ratio, r21, r32) for p in grid]
    for lo, hi, f_lo, f_hi in zip(grid, grid[1:], values, values[1:]):
        if f_lo == 0:
            return lo
        if (f_lo < 0) != (f_hi < 0):
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                f_mid = _celik_residual(mid, log_ratio, r21, r32)
                if (f_mid < 0) == (f_lo < 0):
                    lo, f_lo = mid, f_mid
                else:
                    hi = mid
            return 0.5 * (lo + hi)
    return None


@dataclass
class ThreeGrid:
    """What three runs of one quantity say, the finest first."""
    order: Optional[float]
    status: str  # "ok", "oscillatory", "n/a" or "diverging"
    extrapolated: Optional[float] = None
    gci_fine: Optional[float] = None  # relative, 1.25 |(f2 - f1)/f1| / (r21^p - 1)

    def order_text(self) -> str:
        return fmt(self.order, ".3g") if self.status == "ok" else self.status


def three_grid(f: Sequence[Optional[float]], h: Sequence[float]) -> ThreeGrid:
    """Observed order, Richardson's extrapolated value and Roache's GCI from
    values f = (f1, f2, f3) at cell sizes h = (h1, h2, h3), h1 the finest."""
    f1, f2, f3 = f
    if f1 is None or f2 is None or f3 is None:
        return ThreeGrid(None, "n/a")
    e21, e32 = f2 - f1, f3 - f2
    scale = max(abs(f1), abs(f2), abs(f3))
    if abs(e21) <= VANISHING_CHANGE * scale or abs(e32) <= VANISHING_CHANGE * scale:
        return ThreeGrid(None, "n/a")
    if (e21 < 0) != (e32 < 0):
        return ThreeGrid(None, "oscillatory")
    r21, r32 = h[1] / h[0], h[2] / h[1]
    p = celik_order(e21, e32, r21, r32)
    if p is None:
        return ThreeGrid(None, "diverging")
    factor = r21 ** p - 1.0
    extrapolated = f1 + (f1 - f2) / factor
    gci = GCI_SAFETY_FACTOR * abs((f2 - f1) / f1) / factor if f1 != 0 else None
    return ThreeGrid(p, "ok", extrapolated, gci)


# --------------------------------------------------------------------------
# Runs
# --------------------------------------------------------------------------

@dataclass
class Run:
    scale: Optional[float]
    directory: str
    summary: dict
    note: str = "ran"  # or "reused", "read", ...

    @property
    def cells(self) -> int:
        return int(self.summary.get("cells", 0))

    def failed_checks(self) -> List[str]:
        return [name for name, check in checks_of(self.summary).items()
                if check.get("applies", True) and check.get("pass") is False]

    def checks_text(self) -> str:
        failed = self.failed_checks()
        return "FAIL: " + ", ".join(failed) if failed else "pass"


def fmt(value: Optional[float], spec: str = ".4g") -> str:
    if value is None:
        return "n/a"
    if isinstance(value, bool):
        return str(value).lower()
    return format(value, spec)


def scale_text(scale: float) -> str:
    return format(scale, "g")


def checks_of(summary: dict) -> Dict[str, dict]:
    checks = summary.get("checks", {})
    if isinstance(checks, list):  # a list of {name, ...}: accepted as well
        return {c.get("name", str(i)): c for i, c in enumerate(checks)}
    return checks


def l1_errors(summary: dict) -> Optional[Dict[str, Optional[float]]]:
    """The L1 errors against the exact solution: summary.json's
    ``l1_errors`` object, else the checks l1_density, l1_velocity and
    l1_pressure (at least l1_density); None when the run has neither."""
    errors = summary.get("l1_errors")
    if isinstance(errors, dict):
        return {name: errors.get(name) for name in L1_FIELDS}
    checks = checks_of(summary)
    if "l1_density" not in checks:
        return None
    return {name: checks.get("l1_" + name, {}).get("value") for name in L1_FIELDS}


def read_summary(directory: str) -> Optional[dict]:
    path = os.path.join(directory, "summary.json")
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as error:
        raise StudyError(f"{path}: cannot be read ({error})", EXIT_BAD_INPUT)


def problem_names(exe: str) -> List[str]:
    result = launch([exe, "--list"])
    if result.returncode != 0:
        raise StudyError(f"'{exe} --list' failed with exit code {result.returncode}",
                         EXIT_RUN_FAILED)
    return [line.split()[0] for line in result.stdout.splitlines() if line.strip()]


def launch(command: List[str]) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(command, capture_output=True, text=True)
    except OSError as error:
        raise StudyError(f"cannot start lagremap '{command[0]}': {error.strerror} "
                         "(build it with scripts/build.sh, or name it with --lagremap)",
                         EXIT_RUN_FAILED)


def last_line(text: str) -> str:
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1] if lines else "(no message)"


def run_scale(exe: str, problem: str, mode: Optional[str], scale: float, root: str,
              passthrough: List[str], force: bool) -> Run:
    """One scale's run: reused when its directory holds a finished run of
    the same command line (or one made outside the script), else run."""
    directory = os.path.join(root, "scale_" + scale_text(scale))
    arguments = ["--problem", problem] + (["--mode", mode] if mode else []) + \
        ["--scale", scale_text(scale), "--output", directory, "--quiet"] + passthrough
    summary = read_summary(directory)
    if summary is not None and not force and summary.get("status") == "completed":
        record_path = os.path.join(directory, RECORD)
        if not os.path.exists(record_path):
            note(f"scale {scale_text(scale)}: reusing {directory} (made outside the script)")
            return Run(scale, directory, summary, "reused (made outside the script)")
        with open(record_path) as f:
            if json.load(f).get("arguments") == arguments:
                note(f"scale {scale_text(scale)}: reusing {directory}")
                return Run(scale, directory, summary, "reused")
        note(f"scale {scale_text(scale)}: {directory} was made with other arguments: running again")
    os.makedirs(directory, exist_ok=True)
    for stale in ("summary.json", RECORD):
        if os.path.exists(os.path.join(directory, stale)):
            os.remove(os.path.join(directory, stale))
    note(f"scale {scale_text(scale)}: lagremap {' '.join(arguments)}")
    start = time.monotonic()
    result = launch([exe] + arguments)
    took = time.monotonic() - start
    where = f"{problem}{' --mode ' + mode if mode else ''} --scale {scale_text(scale)}"
    if result.returncode == 2:
        raise StudyError(f"lagremap refused {where}: {last_line(result.stderr)}", EXIT_BAD_INPUT)
    if result.returncode not in (0, 1):
        raise StudyError(f"{where} failed (exit code {result.returncode}): "
                         f"{last_line(result.stderr)}", EXIT_RUN_FAILED)
    summary = read_summary(directory)
    if summary is None:
        raise StudyError(f"{where} wrote no summary.json in {directory}", EXIT_RUN_FAILED)
    with open(os.path.join(directory, RECORD), "w") as f:
        json.dump({"arguments": arguments, "exit_code": result.returncode}, f, indent=1)
    note(f"scale {scale_text(scale)}: {took:.1f} s, exit code {result.returncode}")
    return Run(scale, directory, summary)


def read_scale(root: str, scale: float) -> Run:
    directory = os.path.join(root, "scale_" + scale_text(scale))
    summary = read_summary(directory)
    if summary is None:
        raise StudyError(f"--table-only: no run at scale {scale_text(scale)} "
                         f"({directory}/summary.json is missing)", EXIT_BAD_INPUT)
    return Run(scale, directory, summary, "read")


def note(message: str) -> None:
    print(f"convergence: {message}", file=sys.stderr)


# --------------------------------------------------------------------------
# Cell size
# --------------------------------------------------------------------------

def mesh_axes(summary: dict) -> Optional[List[int]]:
    """The cell counts along x, y, z from summary.json's configuration."""
    config = summary.get("config", {})
    try:
        return [int(config[f"mesh.n{axis}"]) for axis in "xyz"]
    except (KeyError, TypeError, ValueError):
        return None


def refined_directions(runs: List[Run]) -> int:
    """d: the mesh axes of more than one cell (--scale refines those only),
    or, without mesh keys, how the cell count grows with the scale
    (N ~ S^d, the coarsest and finest runs), rounded to 1, 2 or 3."""
    axes = mesh_axes(runs[-1].summary)
    if axes is not None:
        return max(1, sum(1 for n in axes if n > 1))
    coarse, fine = runs[0], runs[-1]
    if coarse.scale is None or fine.scale is None or coarse.scale == fine.scale \
            or coarse.cells <= 0 or fine.cells <= 0:
        return 1
    d = math.log(fine.cells / coarse.cells) / math.log(fine.scale / coarse.scale)
    return min(3, max(1, round(d)))


def cell_sizes(runs: List[Run], dim: int) -> List[float]:
    return [run.cells ** (-1.0 / dim) for run in runs]


# --------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------

def markdown(header: List[str], rows: List[List[str]]) -> List[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return lines


def wall_text(run: Run) -> str:
    """The run's wall seconds; for a run continued with --restart, whose
    summary.json times only the last piece, the steps that piece ran
    (cell-steps per second x wall seconds / cells) against the run's."""
    wall = run.summary.get("wall_seconds")
    text = fmt(wall, ".3g")
    rate = run.summary.get("cell_steps_per_second", {}).get("total")
    steps = run.summary.get("steps")
    if wall and rate and steps and run.cells:
        steps_run = round(rate * wall / run.cells)
        if steps_run < steps:
            text += f" (last piece: {steps_run} of {steps} steps)"
    return text


def error_table(runs: List[Run], h: List[float], errors: List[dict], wall: bool
                ) -> Tuple[List[str], Dict[str, List[Optional[float]]]]:
    """Rows coarse to fine; each order is between a row's run and the one
    above it.  Returns the lines and each field's orders by pair."""
    header = ["scale", "cells", "h", "steps"] + (["wall s"] if wall else [])
    for name in L1_FIELDS:
        header += [f"L1 {name}", "order"]
    header.append("checks")
    rows, orders = [], {name: [] for name in L1_FIELDS}
    for i, run in enumerate(runs):
        row = [fmt(run.scale, "g"), str(run.cells), fmt(h[i], ".4g"),
               str(run.summary.get("steps", "n/a"))] + ([wall_text(run)] if wall else [])
        for name in L1_FIELDS:
            order = None
            if i > 0:
                order = pair_order(errors[i - 1][name], errors[i][name], h[i - 1], h[i])
                orders[name].append(order)
            row += [fmt(errors[i][name], ".4g"), "" if i == 0 else fmt(order, ".3f")]
        row.append(run.checks_text())
        rows.append(row)
    return markdown(header, rows), orders


def check_table(runs: List[Run], h: List[float]
                ) -> Tuple[List[str], Dict[str, List[ThreeGrid]]]:
    """One row per check: reference, value at each scale (coarse to fine),
    the changes between successive scales, and p, f_ext and GCI from the
    finest three runs; a second table gives every triple's p when there are
    more than three runs.  Returns the lines and each check's triples."""
    names: List[str] = []
    for run in runs:
        names += [n for n in checks_of(run.summary) if n not in names]
    fine = runs[-1]
    header = ["check", "reference"] + [f"S = {scale_text(r.scale)}" if r.scale is not None
                                       else os.path.basename(r.directory) for r in runs]
    header += [f"change {scale_text(a.scale)}->{scale_text(b.scale)}" if a.scale is not None
               else "change" for a, b in zip(runs, runs[1:])]
    header += ["order p", "f_ext", "GCI_fine"]
    rows, triples = [], {}
    for name in names:
        values = [checks_of(r.summary).get(name, {}).get("value") for r in runs]
        reference = checks_of(fine.summary).get(name, {})
        ref_text = fmt(reference.get("reference"), ".6g")
        if reference.get("applies") is False:
            ref_text += " (n/a)"
        changes = [fmt(b - a, ".3g") if a is not None and b is not None else "n/a"
                   for a, b in zip(values, values[1:])]
        # three_grid wants the finest first: runs i + 2, i + 1, i.
        triples[name] = [three_grid([values[i + 2], values[i + 1], values[i]],
                                    [h[i + 2], h[i + 1], h[i]])
                         for i in range(len(runs) - 2)]
        last = triples[name][-1] if triples[name] else ThreeGrid(None, "n/a")
        cells = [fmt(v, ".6g") + (" (FAIL)" if name in r.failed_checks() else "")
                 for v, r in zip(values, runs)]
        gci = fmt(100 * last.gci_fine, ".3g") + "%" if last.gci_fine is not None else ""
        rows.append([name, ref_text] + cells + changes +
                    [last.order_text() if len(runs) >= 3 else "n/a (3 scales needed)",
                     fmt(last.extrapolated, ".6g") if last.extrapolated is not None else "",
                     gci])
    lines = markdown(header, rows)
    if len(runs) > 3:
        header = ["check"] + [f"p from S = {', '.join(scale_text(r.scale) for r in runs[i:i + 3])}"
                              for i in range(len(runs) - 2)]
        lines += ["", "Observed order from each triple of successive scales:", ""]
        lines += markdown(header, [[n] + [t.order_text() for t in triples[n]] for n in names])
    return lines, triples


def runs_table(runs: List[Run], h: List[float], wall: bool) -> List[str]:
    header = ["scale", "cells", "h", "steps"] + (["wall s"] if wall else []) + ["checks", "run"]
    rows = [[fmt(r.scale, "g"), str(r.cells), fmt(hh, ".4g"), str(r.summary.get("steps", "n/a"))]
            + ([wall_text(r)] if wall else []) + [r.checks_text(), r.note or "run"]
            for r, hh in zip(runs, h)]
    return markdown(header, rows)


def sweep_table(directories: List[str], wall: bool) -> List[str]:
    """One row per check of every run; the run's columns on its first row."""
    header = ["problem", "mode", "mesh", "cells", "steps"] + (["wall s"] if wall else []) + \
        ["status", "check", "value", "reference", "tolerance", "result"]
    rows = []
    for directory in directories:
        summary = read_summary(directory)
        if summary is None:
            raise StudyError(f"--sweep: {directory} holds no summary.json", EXIT_BAD_INPUT)
        run = Run(None, directory, summary)
        status = summary.get("status", "n/a")
        if status == "completed":
            status = "checks fail" if run.failed_checks() else "pass"
        axes = mesh_axes(summary)
        lead = [str(summary.get("problem", directory)), str(summary.get("mode", "n/a")),
                " x ".join(map(str, axes)) if axes else "n/a", str(run.cells),
                str(summary.get("steps", "n/a"))] + \
            ([wall_text(run)] if wall else []) + [status]
        blank = [""] * len(lead)
        checks = checks_of(summary)
        if not checks:
            rows.append(lead + ["(none)", "", "", "", ""])
        for k, (name, check) in enumerate(checks.items()):
            result = ("pass" if check.get("pass") else "FAIL") if check.get("applies", True) \
                else "n/a"
            rows.append((lead if k == 0 else blank) +
                        [name, fmt(check.get("value"), ".6g"), fmt(check.get("reference"), ".6g"),
                         fmt(check.get("tolerance"), ".3g"), result])
    return markdown(header, rows)


# --------------------------------------------------------------------------
# Plot
# --------------------------------------------------------------------------

def plot(path: str, title: str, curves: List[Tuple[str, List[float], List[float]]],
         ylabel: str) -> bool:
    """Log-log curves (label, h, values) with slope-1 and slope-2 guides
    through the finest point of the first curve; False when matplotlib is
    missing or nothing is positive to draw."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        note("matplotlib is missing: no plot")
        return False
    curves = [(label, [x for x, y in zip(xs, ys) if y is not None and y > 0],
               [y for y in ys if y is not None and y > 0]) for label, xs, ys in curves]
    curves = [c for c in curves if c[1]]
    if not curves:
        note("nothing positive to plot on log axes: no plot")
        return False
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for label, xs, ys in curves:
        ax.loglog(xs, ys, "o-", label=label)
    x0, y0 = curves[0][1][-1], curves[0][2][-1]
    span = [min(min(c[1]) for c in curves), max(max(c[1]) for c in curves)]
    for slope, style in ((1, "k:"), (2, "k--")):
        ax.loglog(span, [y0 * (x / x0) ** slope for x in span], style, lw=0.8,
                  label=f"slope {slope}")
    ax.set_xlabel("cell size h = cells^(-1/d)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return True


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def parse_scales(text: str) -> List[float]:
    try:
        scales = [float(s) for s in text.split(",")]
    except ValueError:
        raise StudyError(f"--scales: '{text}' is not a comma-separated list of numbers",
                         EXIT_BAD_INPUT)
    if len(scales) < 2:
        raise StudyError(f"--scales: '{text}' names fewer than two scales", EXIT_BAD_INPUT)
    if any(not (s > 0 and math.isfinite(s)) for s in scales):
        raise StudyError(f"--scales: '{text}': every scale must be a positive number",
                         EXIT_BAD_INPUT)
    if len(set(scale_text(s) for s in scales)) != len(scales):
        raise StudyError(f"--scales: '{text}' repeats a scale", EXIT_BAD_INPUT)
    return sorted(scales)


def parse_bounds(items: List[str]) -> List[Tuple[str, float]]:
    bounds = []
    for item in items:
        name, _, minimum = item.partition("=")
        try:
            bounds.append((name.strip(), float(minimum)))
        except ValueError:
            raise StudyError(f"--require-order: '{item}' is not NAME=MIN", EXIT_BAD_INPUT)
        if not name.strip():
            raise StudyError(f"--require-order: '{item}' is not NAME=MIN", EXIT_BAD_INPUT)
    return bounds


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise StudyError(message, EXIT_BAD_INPUT)


def parse(argv: List[str]) -> argparse.Namespace:
    passthrough: List[str] = []
    if "--" in argv:
        cut = argv.index("--")
        argv, passthrough = argv[:cut], argv[cut + 1:]
    usage = __doc__.split("Usage:\n")[1].split("\n\n")[0]
    parser = Parser(prog="convergence.py", usage="\n" + usage,
                    description=__doc__.split("\n\n")[0],
                    formatter_class=argparse.RawDescriptionHelpFormatter,
                    epilog="Everything after -- goes to lagremap.  More: the module's docstring "
                           "and docs/running.md.")
    parser.add_argument("problem", nargs="?", help="problem name (lagremap --list)")
    parser.add_argument("--mode", choices=["lagrange", "remap"],
                        help="passed to lagremap (default: lagremap's)")
    parser.add_argument("--scales", default="0.5,1,2", help="comma-separated (default 0.5,1,2)")
    parser.add_argument("--output",
                        help="root of the runs (default out/convergence/PROBLEM[_MODE])")
    parser.add_argument("--lagremap", default=os.path.join(REPO, "build", "lagremap"),
                        help="the binary (default build/lagremap)")
    parser.add_argument("--force", action="store_true", help="rerun runs that are already there")
    parser.add_argument("--table-only", action="store_true",
                        help="run nothing: tabulate the runs already in the output root")
    parser.add_argument("--wall", action="store_true", help="add each run's wall seconds")
    parser.add_argument("--dim", type=int, choices=[1, 2, 3],
                        help="refined directions d of h = cells^(-1/d) (default: the mesh axes of "
                             "more than one cell)")
    parser.add_argument("--require-order", action="append", default=[], metavar="NAME=MIN",
                        help="exit 1 when NAME's observed order is below MIN (repeatable)")
    parser.add_argument("--finest-only", action="store_true",
                        help="--require-order judges the finest pair (triple) only")
    parser.add_argument("--sweep", nargs="+", metavar="RUN_DIR",
                        help="tabulate the checks of these finished runs and exit")
    args = parser.parse_args(argv)
    args.passthrough = passthrough
    if args.sweep is not None:
        if args.problem or passthrough:
            raise StudyError("--sweep takes run directories, not a problem or lagremap "
                             "arguments", EXIT_BAD_INPUT)
        return args
    if not args.problem:
        raise StudyError("name a problem (lagremap --list) or give --sweep RUN_DIR...",
                         EXIT_BAD_INPUT)
    if args.force and args.table_only:
        raise StudyError("--force and --table-only exclude each other", EXIT_BAD_INPUT)
    args.scales = parse_scales(args.scales)
    args.bounds = parse_bounds(args.require_order)
    if args.output is None:
        args.output = os.path.join("out", "convergence",
                                   args.problem + (f"_{args.mode}" if args.mode else ""))
    return args


def judge(bounds: List[Tuple[str, float]], orders: Dict[str, List[Optional[float]]],
          labels: List[str], finest_only: bool) -> Optional[str]:
    """The first bound not met, as one line; None when all are."""
    for name, minimum in bounds:
        if name not in orders:
            raise StudyError(f"--require-order: no quantity '{name}' in this study "
                             f"(there are: {', '.join(orders) or 'none'})", EXIT_BAD_INPUT)
        judged = list(enumerate(orders[name]))
        if finest_only:
            judged = judged[-1:]
        if not judged:
            return f"{name}: no observed order (too few scales)"
        for i, order in judged:
            if order is None or not order >= minimum:
                return (f"{name}: observed order {fmt(order, '.3f')} {labels[i]} "
                        f"is below {minimum:g}")
    return None


@dataclass
class Section:
    """A study's table and what goes with it: each quantity's orders (by pair
    or triple, coarse to fine) with the labels of those pairs or triples,
    and the plot's curves (label, h, values) and y label."""
    lines: List[str]
    orders: Dict[str, List[Optional[float]]]
    labels: List[str]
    curves: List[Tuple[str, List[float], List[Optional[float]]]]
    what: str
    ylabel: str


def exact_section(runs: List[Run], h: List[float], errors: List[dict], wall: bool) -> Section:
    table, orders = error_table(runs, h, errors, wall)
    lines = ["L1 error against the exact solution; order: the observed order between the row "
             "and the row above, ln(e_coarse/e_fine)/ln(h_coarse/h_fine).", ""] + table
    labels = [f"between scales {scale_text(a.scale)} and {scale_text(b.scale)}"
              for a, b in zip(runs, runs[1:])]
    curves = []
    for name in L1_FIELDS:
        values = [e[name] for e in errors]
        if any(v is not None for v in values):
            last = orders[name][-1] if orders[name] else None
            curves.append((f"L1 {name} (finest order {fmt(last, '.2f')})", h, values))
    return Section(lines, orders, labels, curves, "L1 error against the exact solution",
                   "L1 error")


def checks_section(runs: List[Run], h: List[float], wall: bool) -> Section:
    table, triples = check_table(runs, h)
    lines = ["Each check at each scale S (FAIL: the check failed there), its change between "
             "successive scales, and from the finest three: the observed order p (Celik et al. "
             "2008), Richardson's extrapolated value f_ext and Roache's GCI_fine (safety "
             "factor 1.25).", ""] + runs_table(runs, h, wall) + [""] + table
    orders = {name: [t.order for t in ts] for name, ts in triples.items()}
    labels = [f"from scales {', '.join(scale_text(r.scale) for r in runs[i:i + 3])}"
              for i in range(len(runs) - 2)]
    curves = []
    for name, ts in triples.items():
        values = [checks_of(r.summary).get(name, {}).get("value") for r in runs]
        if all(v is None or abs(v) < ROUND_OFF_CHECK for v in values):
            note(f"{name} is at round-off at every scale: left out of the plot")
            continue
        changes = [abs(b - a) / abs(b) if a is not None and b is not None and b != 0 else None
                   for a, b in zip(values, values[1:])]
        curves.append((f"{name} (p {ts[-1].order_text() if ts else 'n/a'})", h[1:], changes))
    return Section(lines, orders, labels, curves,
                   "change of each check between successive scales",
                   "|f_coarse - f_fine| / |f_fine|")


def study(args: argparse.Namespace) -> int:
    if args.table_only:
        runs = [read_scale(args.output, s) for s in args.scales]
    else:
        names = problem_names(args.lagremap)
        if args.problem not in names:
            raise StudyError(f"unknown problem '{args.problem}' (lagremap --list: "
                             f"{', '.join(names)})", EXIT_BAD_INPUT)
        runs = [run_scale(args.lagremap, args.problem, args.mode, s, args.output,
                          args.passthrough, args.force) for s in args.scales]
    dim = args.dim or refined_directions(runs)
    h = cell_sizes(runs, dim)
    problem = runs[-1].summary.get("problem", args.problem)
    mode = runs[-1].summary.get("mode", args.mode or "")
    errors = [l1_errors(r.summary) for r in runs]
    if all(e is not None for e in errors):
        section = exact_section(runs, h, errors, args.wall)
    else:
        if any(e is not None for e in errors):
            note("some runs have L1 errors and some not: tabulating the checks")
        section = checks_section(runs, h, args.wall)
    title = f"**`{problem}` ({mode})**, scales {', '.join(scale_text(s) for s in args.scales)}"
    if args.passthrough:
        title += f", `{' '.join(args.passthrough)}`"
    text = "\n".join([title + f"; h = cells^(-1/{dim}) ({dim} refined "
                      f"direction{'s' if dim > 1 else ''}).", ""] + section.lines) + "\n"
    print(text, end="")
    os.makedirs(args.output, exist_ok=True)
    with open(os.path.join(args.output, "convergence.md"), "w") as f:
        f.write(text)
    png = os.path.join(args.output, "convergence.png")
    drawn = plot(png, f"{problem} ({mode}): {section.what}", section.curves, section.ylabel)
    note(f"wrote {os.path.join(args.output, 'convergence.md')}" + (f" and {png}" if drawn else ""))
    failure = judge(args.bounds, section.orders, section.labels, args.finest_only)
    if failure:
        print(f"convergence: {problem} ({mode}): {failure}", file=sys.stderr)
        return EXIT_ORDER_BELOW
    return 0


def main(argv: List[str]) -> int:
    try:
        args = parse(argv)
        if args.sweep is not None:
            print("\n".join(sweep_table(args.sweep, args.wall)))
            return 0
        return study(args)
    except StudyError as error:
        print(f"convergence: error: {error}", file=sys.stderr)
        return error.status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
