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
"""

import argparse
import csv
import glob
import json
import math
import os
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import partial
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np
import matplotlib

matplotlib.use("Agg")  # never needs a display: runs in CI and over ssh
import matplotlib.pyplot as plt  # noqa: E402  (must follow matplotlib.use)
from matplotlib import patheffects  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import SymmetricalLogLocator  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

DPI = 120
EXIT_PLOT_FAILED = 1
EXIT_BAD_DIR = 2

# Slice maps: a hull triangle is taken as bridging a gap (not covering cells)
# when its circumradius exceeds this many local cell spacings; see
# triangulate_points.  A right triangle over a single missing cell has ~0.7,
# a well-shaped one between stretched cells 2-3.
HULL_MASK_RATIO = 5.0

# Axis labels with SI units, shared by every plot that shows the quantity so
# the same field is labelled the same way in every figure.
LABELS = {
    "x": "x [m]",
    "y": "y [m]",
    "r": "r [m]",
    "t": "t [s]",
    "dt": "Δt [s]",
    "rho": "density ρ [kg/m³]",
    "u": "velocity u [m/s]",
    "p": "pressure p [Pa]",
    "e": "specific internal energy e [J/kg]",
    "speed": "speed |u| [m/s]",
    "sigma_xx": "stress σ_xx [Pa]",
}

# Fixed colours per time-step limiter, so the same reason has the same colour
# in every run and runs can be compared side by side.  Unknown reasons (the
# C++ side may add some) get the remaining colours of the default cycle.
DT_REASON_COLOURS = {
    "cfl": "tab:blue",
    "volume": "tab:orange",
    "growth": "tab:green",
    "end": "tab:red",
    "initial": "tab:purple",
}
SPARE_COLOURS = ["tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray"]


class InputError(Exception):
    """An input file exists but its contents cannot be plotted."""


class SkipPlot(Exception):
    """An optional input of a plot (a field, the h5py module) is missing: the
    plot is skipped with a note, which is not an error."""


# --------------------------------------------------------------------------
# Input
# --------------------------------------------------------------------------

def read_csv(path: str) -> Dict[str, np.ndarray]:
    """Read a CSV with a header row into {column name: array}.

    Columns that parse as numbers become float arrays (C++ streams may write
    ``nan``, ``-nan`` or ``inf``, which Python's float() accepts); any other
    column, e.g. history's dt_reason, stays an array of stripped strings.
    The csv module is used instead of np.genfromtxt because it is several
    times faster on the ~250k-row radial files and handles mixed types.
    """
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and any(c.strip() for c in r)]
    if not rows:
        raise InputError(f"{path}: empty file (no header)")
    header = [h.strip() for h in rows[0]]
    body = rows[1:]
    for lineno, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise InputError(f"{path}:{lineno}: {len(row)} fields, header has "
                             f"{len(header)}")
    columns = {}
    for i, name in enumerate(header):
        values = [row[i].strip() for row in body]
        try:
            columns[name] = np.array([float(v) for v in values], dtype=float)
        except ValueError:
            columns[name] = np.array(values, dtype=str)
    return columns


def require(table: Dict[str, np.ndarray], names: List[str], path: str) -> None:
    """Fail with a clear message if a CSV lacks a column a plot needs.

    The formats are fixed by the C++ writer; a missing column means the two
    sides disagree, which should be reported rather than silently skipped.
    """
    missing = [n for n in names if n not in table]
    if missing:
        raise InputError(f"{os.path.basename(path)}: missing column(s) "
                         f"{', '.join(missing)}")
    if len(table[names[0]]) == 0:
        raise InputError(f"{os.path.basename(path)}: header only, no data rows")


class Run:
    """A run directory: its summary plus lazily read, cached CSV files and
    HDF5 snapshots.

    Caching matters because radial.csv (up to ~250k rows) feeds two figures
    and should be parsed once.  ``partner`` is the run of the other mode the
    overlays compare it with (set by main, None when there is none).
    """

    def __init__(self, directory: str, summary: dict):
        self.dir = directory
        self.summary = summary
        self.partner: Optional["Run"] = None
        self.extras: List["Run"] = []  # --also: more runs of the problem to overlay
        self._tables: Dict[str, Dict[str, np.ndarray]] = {}
        self._snapshots: Optional[List["Snapshot"]] = None

    @property
    def mode(self) -> str:
        return str(self.summary.get("mode", "lagrange"))

    @property
    def problem(self) -> str:
        return str(self.summary.get("problem", ""))

    def path(self, name: str) -> str:
        return os.path.join(self.dir, name)

    def has(self, name: str) -> bool:
        return os.path.isfile(self.path(name))

    def table(self, name: str, columns: List[str]) -> Dict[str, np.ndarray]:
        if name not in self._tables:
            self._tables[name] = read_csv(self.path(name))
        table = self._tables[name]
        require(table, columns, self.path(name))
        return table

    def check(self, name: str) -> Optional[dict]:
        """Return summary["checks"][name] if it is a dict, else None."""
        c = (self.summary.get("checks") or {}).get(name)
        return c if isinstance(c, dict) else None

    def config_int(self, key: str) -> Optional[int]:
        """An integer key of the run's configuration (summary["config"]),
        or None when absent or not an integer."""
        value = (self.summary.get("config") or {}).get(key)
        try:
            return int(str(value))
        except ValueError:
            return None

    def snapshots(self) -> List["Snapshot"]:
        """The run's HDF5 snapshots in time order (empty when it wrote none)."""
        if self._snapshots is None:
            shape = (self.config_int("mesh.nx"), self.config_int("mesh.ny"))
            self._snapshots = list_snapshots(self.dir, shape)
        return self._snapshots

    def solid_materials(self, snapshot: "Snapshot") -> List[int]:
        """Indices of the solid materials of a multi-material snapshot.

        summary.json's interfaces block says which materials are solids;
        without it (runs older than the flag) every material but the last is
        taken: the problems list the gas last.
        """
        present = list(range(snapshot.n_materials))
        interfaces = self.summary.get("interfaces")
        flags = [(interfaces or {}).get(f"material_{k}", {}) for k in present]
        if not all(isinstance(f, dict) and "solid" in f for f in flags):
            return present[:-1] or present
        return [k for k, f in zip(present, flags) if f["solid"]]


def read_run(directory: str) -> Run:
    """Open a run directory; InputError with a one-line reason if it is not one.

    summary.json is the marker of a lagremap run directory and carries the
    problem name that selects the plots, so without it nothing can be done.
    """
    if not os.path.isdir(directory):
        raise InputError(f"{directory}: no such directory")
    summary_path = os.path.join(directory, "summary.json")
    if not os.path.isfile(summary_path):
        raise InputError(f"{directory}: no summary.json (not a lagremap output directory?)")
    try:
        with open(summary_path) as f:
            summary = json.load(f)
    except (OSError, ValueError) as exc:
        raise InputError(f"{summary_path}: unreadable: {' '.join(str(exc).split())}")
    if not isinstance(summary, dict):
        raise InputError(f"{summary_path}: top level is not a JSON object")
    return Run(directory, summary)


def load_run(directory: str) -> Run:
    """Open DIR or exit 2 with a one-line message."""
    try:
        return read_run(directory)
    except InputError as exc:
        fail(str(exc))
        raise  # not reached: fail exits


def fail(message: str) -> None:
    """Print a one-line error and exit 2 (the documented bad-input status)."""
    print(f"plot.py: error: {message}", file=sys.stderr)
    sys.exit(EXIT_BAD_DIR)


def note(message: str) -> None:
    """A one-line remark on stderr: an optional input is missing and what is
    drawn instead.  Not an error (the exit status is unchanged)."""
    print(f"plot.py: note: {message}", file=sys.stderr)


# --------------------------------------------------------------------------
# The lagrange run an overlay compares a remap run with
# --------------------------------------------------------------------------

def partner_candidates(run: Run) -> List[str]:
    """Where a remap run's lagrange reference usually is: a sibling directory
    named after it (``out/taylor`` -> ``out/taylor_lagrange``, what
    scripts/run.sh writes), or after the problem."""
    directory = os.path.normpath(run.dir)
    parent, base = os.path.split(directory)
    names = [base + "_lagrange", base + "-lagrange"]
    if "remap" in base:
        names.append(base.replace("remap", "lagrange"))
    if run.problem:
        names += [run.problem + "_lagrange", run.problem + "-lagrange",
                  os.path.join("lagrange", run.problem)]
    paths = []
    for name in names:
        path = os.path.join(parent, name)
        if os.path.normpath(path) != directory and path not in paths:
            paths.append(path)
    return paths


def find_partner(run: Run, compare: Optional[str], auto: bool) -> Optional[Run]:
    """The run to overlay with DIR's: --compare's, else (remap runs) a
    lagrange run found next to DIR.  Missing or unsuitable: a note, None."""
    if compare:
        try:
            partner = read_run(compare)
        except InputError as exc:
            note(f"--compare: {exc}; drawing {run.dir} alone")
            return None
    elif auto and run.mode == "remap":
        found = [p for p in partner_candidates(run)
                 if os.path.isfile(os.path.join(p, "summary.json"))]
        partner = None
        for path in found:
            try:
                candidate = read_run(path)
            except InputError:
                continue
            if candidate.mode == "lagrange" and candidate.problem == run.problem:
                partner = candidate
                break
        if partner is None:
            note(f"no lagrange run of {run.problem or '?'} next to {run.dir} "
                 f"(looked for {', '.join(os.path.basename(p) for p in partner_candidates(run)[:2])}); "
                 f"the overlays show the remap run alone (--compare LAGRANGE_DIR names one)")
            return None
    else:
        return None
    if partner.problem != run.problem:
        note(f"--compare: {partner.dir} is a '{partner.problem}' run, not "
             f"'{run.problem}'; drawing {run.dir} alone")
        return None
    if os.path.realpath(partner.dir) == os.path.realpath(run.dir):
        return None
    return partner


# Line style per mode, the paper's convention: lagrange solid, remap dashed.
MODE_STYLE = {
    "lagrange": {"ls": "-", "color": "tab:blue"},
    "remap": {"ls": "--", "color": "tab:red"},
}
SECOND_STYLE = {"ls": ":", "color": "tab:green"}  # a compared run of the same mode
EXTRA_STYLES = [{"ls": "-.", "color": "tab:purple"}, {"ls": ":", "color": "tab:orange"}]
LINE_WORDS = {"-": "solid", "--": "dashed", ":": "dotted"}


@dataclass
class Curve:
    """One run as drawn in an overlay: its label and line style."""
    run: Run
    label: str
    style: Dict[str, str]


def overlay_runs(run: Run) -> List[Curve]:
    """DIR's run and its partner, lagrange first (drawn under the remap one).

    Two runs of the same mode (a --compare between two remap runs) are told
    apart by their directory names and a dotted second line."""
    runs = [run] + ([run.partner] if run.partner is not None else [])
    runs.sort(key=lambda r: 0 if r.mode == "lagrange" else 1)
    same_mode = len(runs) == 2 and runs[0].mode == runs[1].mode
    curves = []
    for i, r in enumerate(runs):
        label = r.mode
        if same_mode:
            label += f" ({os.path.basename(os.path.normpath(r.dir))})"
        elif closure_of(r) and any(closure_of(x) for x in run.extras):
            label += f" ({closure_of(r)})"
        style = dict(SECOND_STYLE if same_mode and i == 1
                     else MODE_STYLE.get(r.mode, MODE_STYLE["lagrange"]))
        curves.append(Curve(r, label, style))
    # further runs of the same problem (--also: e.g. the other mixed-cell closure)
    for i, r in enumerate(run.extras):
        label = f"{r.mode} ({closure_of(r) or os.path.basename(os.path.normpath(r.dir))})"
        curves.append(Curve(r, label, dict(EXTRA_STYLES[i % len(EXTRA_STYLES)])))
    return curves


def closure_of(run: Run) -> Optional[str]:
    """The mixed-cell closure of a remap run (summary's mixture.closure)."""
    return ((run.summary or {}).get("config") or {}).get("mixture.closure")


def curve_tables(run: Run, name: str, columns: List[str]) -> List[Tuple[Curve, Dict[str, np.ndarray]]]:
    """The CSV `name` of every run of the overlay.  DIR's own must be
    readable (InputError otherwise); a partner without it is left out with
    a note, so the figure still shows DIR's run."""
    result = []
    for curve in overlay_runs(run):
        if curve.run is run:
            result.append((curve, run.table(name, columns)))
            continue
        if not curve.run.has(name):
            note(f"{curve.run.dir} has no {name}; {name} drawn without its {curve.label} curve")
            continue
        try:
            result.append((curve, curve.run.table(name, columns)))
        except InputError as exc:
            note(f"{curve.run.dir}: {exc}; drawn without its {curve.label} curve")
    return result


def pair_title(run: Run, what: str) -> str:
    """Title of an overlay: the runs it compares, or run_title's line alone."""
    if run.partner is None:
        return run_title(run, what)
    parts = []
    for curve in overlay_runs(run):
        s = curve.run.summary
        cells = f", {s['cells']} cells" if "cells" in s else ""
        line = LINE_WORDS.get(curve.style.get("ls", ""), "points")
        parts.append(f"{curve.label} ({line}{cells})")
    t_end = run.summary.get("t_end")
    when = f", t = {fmt_num(t_end)} s" if t_end is not None else ""
    return f"{what}\n{run.problem}: " + " vs ".join(parts) + when


# --------------------------------------------------------------------------
# Formatting helpers
# --------------------------------------------------------------------------

def fmt_num(value, spec: str = ".3g", missing: str = "?") -> str:
    """Format a number from JSON, tolerating absent or non-numeric values."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return format(value, spec)
    return missing


def run_title(run: Run, what: str) -> str:
    """Common first title line, so every figure says which run it shows."""
    s = run.summary
    parts = [str(s.get("problem", "?"))]
    if "mode" in s:
        parts.append(str(s["mode"]))
    if "order" in s:
        parts.append(f"order {s['order']}")
    if "cells" in s:
        parts.append(f"{s['cells']} cells")
    if "t_end" in s:
        parts.append(f"t = {fmt_num(s['t_end'])} s")
    return f"{what}: " + ", ".join(parts)


def check_text(check: Optional[dict], label: str) -> Optional[str]:
    """Describe a summary check as 'label = v (tolerance t, PASS)'."""
    if check is None or "value" not in check:
        return None
    text = f"{label} = {fmt_num(check['value'], '.3e')}"
    extras = []
    if "tolerance" in check:
        extras.append(f"tolerance {fmt_num(check['tolerance'], '.2e')}")
    if check.get("applies") is False:
        extras.append("n/a: " + check.get("not_applicable", "not this case"))
    elif "pass" in check:
        extras.append("PASS" if check["pass"] else "FAIL")
    return text + (f" ({', '.join(extras)})" if extras else "")


def save(fig, out_path: str) -> str:
    """Write the figure at the project-wide DPI and free its memory."""
    fig.savefig(out_path, dpi=DPI)
    plt.close(fig)
    return out_path


# --------------------------------------------------------------------------
# Problem-specific plots
# --------------------------------------------------------------------------

def plot_sod_profiles(run: Run, out_path: str) -> str:
    """Sod shock tube: numeric vs exact density, velocity, pressure, energy.

    Numeric values are markers and the exact Riemann solution a line, so
    over- and undershoots at the shock and contact, and the smearing width,
    are visible per cell.  The L1 density error from the summary goes in the
    title because it is the number the regression check judges.
    """
    name = "sod_profile.csv"
    fields = ["rho", "u", "p", "e"]
    t = run.table(name, ["x"] + fields)
    order = np.argsort(t["x"], kind="stable")
    x = t["x"][order]

    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    for ax, field in zip(axes.flat, fields):
        exact = t.get(f"{field}_exact")
        if exact is not None and exact.dtype.kind == "f":
            ax.plot(x, exact[order], "-", color="black", lw=1.2,
                    label="exact", zorder=1)
        ax.plot(x, t[field][order], "o", ms=3, mfc="none", mew=0.8,
                color="tab:blue", label="lagremap", zorder=2)
        ax.set_ylabel(LABELS[field])
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    for ax in axes[-1]:
        ax.set_xlabel(LABELS["x"])

    title = run_title(run, "Sod shock tube")
    l1 = check_text(run.check("l1_density"), "L1 density error")
    if l1:
        title += "\n" + l1
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)


def plot_wilkins_profiles(run: Run, out_path: str) -> str:
    """Flyer plate: density, velocity and sigma_xx along x (paper Fig. 3),
    lagrange solid and remap dashed when both runs are at hand.

    Thin horizontal lines mark the exact plastic state and elastic precursor
    levels of the default impact, so the two-wave structure (precursor
    plateau ahead of the plastic shock) can be judged by eye.

    The figure shows the aluminium only.  A remap run also holds the light
    gas behind the flyer (x from -0.04 to the flyer's back face): its cells
    (alpha_al < 1/2) are left out, the density drawn is aluminium's own
    (rho_al, not the cell's mixture density, which falls to ~1 kg/m3 over
    the smeared back face), and the x axis spans the aluminium of the runs,
    the lagrange run's whole mesh, so both curves fill the same frame.
    Profiles written before the alpha_al column are drawn whole.
    """
    fields = ["rho", "u", "sigma_xx"]
    curves = curve_tables(run, "wilkins_profile.csv", ["x"] + fields)
    exact = {"rho": (2985.6, 2800.2), "u": (400.0, 35.2), "sigma_xx": (-6.637e9, -0.636e9)}
    drawn = []  # (curve, {field: values on the aluminium cells, in x order})
    gas_note = None
    for curve, t in curves:
        order = np.argsort(t["x"], kind="stable")
        keep = np.ones(len(order), dtype=bool)
        columns = {f: t[f][order] for f in ["x"] + fields}
        alpha = t.get("alpha_al")
        if alpha is not None and alpha.dtype.kind == "f":
            keep = alpha[order] >= 0.5
            if "rho_al" in t and t["rho_al"].dtype.kind == "f":
                columns["rho"] = t["rho_al"][order]
            if not keep.all() and keep.any():
                x_gas = columns["x"][~keep]
                gas_note = (f"{curve.label}: cells with alpha_al < 1/2 (the gas, "
                            f"x ≤ {x_gas.max():.4g} m) not drawn; ρ of the aluminium")
        drawn.append((curve, {f: v[keep] for f, v in columns.items()}))
    fig, axes = plt.subplots(3, 1, figsize=(9, 9.5), sharex=True)
    for ax, field in zip(axes, fields):
        plastic, precursor = exact[field]
        ax.axhline(plastic, ls="-", lw=0.6, color="0.35", label="exact plastic state")
        ax.axhline(precursor, ls="-.", lw=0.6, color="0.35", label="exact elastic precursor")
        for curve, columns in drawn:
            ax.plot(columns["x"], columns[field], lw=1.2, label=curve.label, **curve.style)
        ax.set_ylabel(LABELS[field])
        ax.grid(alpha=0.3)
    xs = [columns["x"] for _, columns in drawn if len(columns["x"])]
    if xs:
        lo = min(x.min() for x in xs)
        hi = max(x.max() for x in xs)
        pad = 0.02 * (hi - lo)
        axes[-1].set_xlim(lo - pad, hi + pad)
    axes[0].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel(LABELS["x"])
    title = pair_title(run, "Wilkins flyer plate")
    if gas_note:
        title += "\n" + gas_note
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)


def plot_pile_wall_stress(run: Run, out_path: str) -> str:
    """Pile driving: wall sigma_xx against time with the exact square wave,
    lagrange solid and remap dashed when both runs are at hand.

    The exact linear-elastic answer is 0 / twice the imposed stress / 0 on
    [0, L/c] / [L/c, 3L/c] / [3L/c, 4L/c]; overshoot at the fronts and the
    arrival time are what to look at.
    """
    curves = curve_tables(run, "pile_wall_stress.csv", ["t", "sigma_xx", "exact"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    own = next(t for curve, t in curves if curve.run is run)
    ax.plot(own["t"], own["exact"], "-", color="black", lw=0.8,
            label="exact (linear elastic)")
    for curve, t in curves:
        ax.plot(t["t"], t["sigma_xx"], lw=1.2, label=curve.label, **curve.style)
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("wall stress σ_xx [Pa]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(pair_title(run, "Pile driving: stress on the wall"))
    fig.tight_layout()
    return save(fig, out_path)


def paper_number(runs: List[Run], check: str, mode: str) -> Optional[float]:
    """The paper's number for `check` in `mode`: the `paper` field of that
    mode's run, or the `lagrange_reference` a remap run records."""
    for r in runs:
        c = r.check(check) or {}
        if r.mode == mode and isinstance(c.get("paper"), (int, float)):
            return float(c["paper"])
    if mode == "lagrange":
        for r in runs:
            c = r.check(check) or {}
            if r.mode == "remap" and isinstance(c.get("lagrange_reference"), (int, float)):
                return float(c["lagrange_reference"])
    return None


def plot_taylor(run: Run, out_path: str) -> str:
    """Taylor impact: this run's cells coloured by density at t_end (the
    mushroom at the wall) and the bar length against time, lagrange solid and
    remap dashed, with the paper's final lengths."""
    mesh_name = "taylor_mesh_z0.csv"
    cells = run.table(mesh_name, CORNER_COLUMNS + ["density"])
    polys = slice_polygons(cells, run.path(mesh_name))
    fig, (ax_bar, ax_len) = plt.subplots(1, 2, figsize=(13, 4.8),
                                         gridspec_kw={"width_ratios": [1.6, 1]})
    art = draw_cells(ax_bar, polys, cells["density"])
    fig.colorbar(art, ax=ax_bar, label=LABELS["rho"], shrink=0.8)
    ax_bar.autoscale_view()
    ax_bar.set_aspect("equal")
    ax_bar.set_xlabel(LABELS["x"])
    ax_bar.set_ylabel(LABELS["y"])
    ax_bar.set_title("Deformed bar at t_end" if run.mode != "remap"
                     else "Density on the fixed mesh at t_end (bar in gas)")
    curves = curve_tables(run, "taylor_length.csv", ["t", "length"])
    for curve, history in curves:
        how = ("aluminium volume along the axis" if curve.run.mode == "remap"
               else "largest node x")
        ax_len.plot(history["t"], history["length"], lw=1.2,
                    label=f"{curve.label} ({how})", **curve.style)
        final = curve.run.check("final_length")
        if final and isinstance(final.get("value"), (int, float)):
            how = "α = 0.5 on the axis" if curve.run.mode == "remap" else "final"
            ax_len.plot([history["t"][-1]], [final["value"]], "o", mfc="none",
                        color=curve.style["color"],
                        label=f"{curve.label} {how}: {final['value']:.3f} m")
    runs = [curve.run for curve, _ in curves]
    for mode, ls in (("lagrange", "-"), ("remap", "--")):
        paper = paper_number(runs, "final_length", mode)
        if paper is not None:
            ax_len.axhline(paper, ls=ls, lw=0.6, color="black",
                           label=f"paper ({mode}) {paper:g} m")
    ax_len.set_xlabel(LABELS["t"])
    ax_len.set_ylabel("bar length [m]")
    ax_len.grid(alpha=0.3)
    ax_len.legend(loc="best", fontsize="small")
    fig.suptitle(pair_title(run, "Taylor impact"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_taylor_outline(run: Run, out_path: str) -> str:
    """Taylor impact, the paper's Fig. 6: the bar's outline at t_end, the
    deformed Lagrangian mesh's boundary (solid) over the alpha = 0.5 contour
    of aluminium on the fixed remap mesh (dashed), with the initial bar."""
    fig, ax = plt.subplots(figsize=(11, 5))
    handles = []
    frame = []  # points the view must hold
    initial_drawn = False
    for curve in overlay_runs(run):
        r = curve.run
        snaps = r.snapshots()
        if not snaps:
            note(f"{r.dir}: no HDF5 snapshots; the outline has no {curve.label} curve")
            continue
        final = snaps[-1]
        final_length = (r.check("final_length") or {}).get("value")
        length = f", L = {final_length:.3f} m" if isinstance(final_length, (int, float)) else ""
        if final.n_materials > 1:
            materials = r.solid_materials(final)
            for k in materials:
                draw_alpha_contour(ax, final, k, colors=curve.style["color"],
                                   linestyles=curve.style["ls"], linewidths=1.4)
            handles.append(Line2D([], [], lw=1.4, **curve.style,
                                  label=f"{curve.label}: α = 0.5 of aluminium{length}"))
            if not initial_drawn and snaps[0] is not final:
                for k in materials:
                    draw_alpha_contour(ax, snaps[0], k, colors="0.55",
                                       linestyles=":", linewidths=0.9)
                frame.append(snaps[0].solid_extent(materials))
                initial_drawn = True
        else:
            segments = final.outline_segments()
            ax.add_collection(LineCollection(segments, colors=curve.style["color"],
                                             linestyles=curve.style["ls"], linewidths=1.4))
            handles.append(Line2D([], [], lw=1.4, **curve.style,
                                  label=f"{curve.label}: boundary of the deformed mesh{length}"))
            if snaps[0] is not final:
                initial = snaps[0].outline_segments()
                ax.add_collection(LineCollection(initial, colors="0.55",
                                                 linestyles=":", linewidths=0.9))
                frame.append(initial.reshape(-1, 2))
                initial_drawn = True
            frame.append(segments.reshape(-1, 2))
        frame.append(final.layer_polygons().reshape(-1, 2) if final.n_materials == 1
                     else final.solid_extent(r.solid_materials(final)))
    if not handles:
        raise InputError("no run of the pair has HDF5 snapshots")
    if initial_drawn:
        handles.append(Line2D([], [], ls=":", color="0.55", lw=0.9, label="initial bar"))
    points = np.concatenate([f for f in frame if f is not None and len(f)])
    lo, hi = points.min(axis=0), points.max(axis=0)
    pad = 0.04 * float((hi - lo).max())
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(LABELS["x"])
    ax.set_ylabel(LABELS["y"])
    ax.grid(alpha=0.3)
    ax.legend(handles=handles, loc="upper right", fontsize="small")
    ax.set_title(pair_title(run, "Taylor impact, outline at t_end"))
    fig.tight_layout()
    return save(fig, out_path)


def rod_outline(cells: Dict[str, np.ndarray], polys: np.ndarray):
    """The rod's outline in its symmetry plane z = 0: a lagrange run's outer
    cell edges (those no other cell shares), or None for a remap run (whose
    outline is the alpha = 1/2 contour of copper)."""
    if not np.all(cells["alpha_cu"] == 1.0):
        return None
    edges: Dict[Tuple, int] = {}
    for poly in np.round(polys, 12):
        for k in range(4):
            a, b = tuple(poly[k]), tuple(poly[(k + 1) % 4])
            key = (a, b) if a < b else (b, a)
            edges[key] = edges.get(key, 0) + 1
    return np.array([key for key, count in edges.items() if count == 1])


def plot_rod(run: Run, out_path: str) -> str:
    """3D Taylor rod, like a Taylor test report: the final profile in the
    symmetry plane z = 0 over the initial rod (lagrange: the deformed mesh's
    boundary; remap: the alpha = 1/2 contour of copper), the plastic strain
    in that plane, and the rod length against time with the published band
    (lagrange solid, remap dashed)."""
    name = "rod_plane_z0.csv"
    fig, (ax_rod, ax_len) = plt.subplots(1, 2, figsize=(14, 4.8),
                                         gridspec_kw={"width_ratios": [1.7, 1]})
    handles = []
    art = None
    for curve in overlay_runs(run):
        r = curve.run
        if not r.has(name):
            continue
        cells = r.table(name, CORNER_COLUMNS + ["alpha_cu", "plastic_strain"])
        polys = slice_polygons(cells, r.path(name)) * 1e3
        outline = rod_outline(cells, polys)
        if r is run:  # this run's plastic strain (copper's cells)
            strain = np.where(cells["alpha_cu"] >= 0.5, cells["plastic_strain"], np.nan)
            art = draw_cells(ax_rod, polys, strain, cmap="magma")
        if outline is not None:
            ax_rod.add_collection(LineCollection(outline, colors=curve.style["color"],
                                                 linestyles=curve.style["ls"], linewidths=1.3))
            what = "boundary of the deformed mesh"
        else:
            centre = polys.mean(axis=1)
            ax_rod.tricontour(centre[:, 0], centre[:, 1], cells["alpha_cu"], levels=[0.5],
                              colors=curve.style["color"], linestyles=curve.style["ls"],
                              linewidths=1.3)
            what = "α = 1/2 of copper"
        length = (r.check("final_length") or {}).get("value")
        radius = (r.check("mushroom_radius") or {}).get("value")
        numbers = ""
        if isinstance(length, (int, float)) and isinstance(radius, (int, float)):
            numbers = f": L = {length * 1e3:.2f} mm, R = {radius * 1e3:.2f} mm"
        handles.append(Line2D([], [], lw=1.3, **curve.style,
                              label=f"{curve.label}, {what}{numbers}"))
    if art is None:
        raise InputError(f"{run.dir}: no {name}")
    config = run.summary.get("config", {})
    length0 = float(config.get("rod.length", 32.4e-3)) * 1e3
    radius0 = float(config.get("rod.radius", 3.2e-3)) * 1e3
    ax_rod.plot([0, length0, length0], [radius0, radius0, 0], ls=":", color="0.5", lw=0.9)
    handles.append(Line2D([], [], ls=":", color="0.5", lw=0.9, label="initial rod"))
    fig.colorbar(art, ax=ax_rod, label="equivalent plastic strain", shrink=0.8)
    ax_rod.set_xlim(-0.5, length0 + 0.5)
    ax_rod.set_ylim(0, max(2.6 * radius0, 8.0))
    ax_rod.set_aspect("equal")
    ax_rod.set_xlabel("x [mm]")
    ax_rod.set_ylabel("y [mm] (plane z = 0)")
    ax_rod.legend(handles=handles, loc="upper right", fontsize="small")
    ax_rod.set_title("Profile and plastic strain at t_end")
    for curve, history in curve_tables(run, "rod_length.csv", ["t", "length"]):
        how = ("copper volume along the axis" if curve.run.mode == "remap"
               else "largest node x")
        ax_len.plot(history["t"] * 1e6, history["length"] * 1e3, lw=1.2,
                    label=f"{curve.label} ({how})", **curve.style)
    band = run.check("final_length") or {}
    if isinstance(band.get("reference"), (int, float)) and band.get("tolerance"):
        ref, tol = band["reference"] * 1e3, band["tolerance"] * 1e3
        ax_len.axhspan(ref - tol, ref + tol, color="0.85",
                       label=f"reference {ref:.2f} ± {tol:.2f} mm")
    ax_len.set_xlabel("t [µs]")
    ax_len.set_ylabel("rod length [mm]")
    ax_len.grid(alpha=0.3)
    ax_len.legend(loc="best", fontsize="small")
    fig.suptitle(pair_title(run, "Taylor anvil test of a round rod (3D)"))
    fig.tight_layout()
    return save(fig, out_path)


# Colours of the shell's radii, one per CSV column (any other column gets a
# spare colour), the line style says the mode.
SHELL_RADIUS_COLOURS = {
    "inner_radius": "tab:blue",
    "outer_radius_incompressible": "tab:orange",
    "outer_radius_be_area": "tab:green",
    "outer_radius": "tab:green",
}
SHELL_RADIUS_WORDS = {
    "inner_radius": "inner",
    "outer_radius_incompressible": "outer (shell area conserved)",
    "outer_radius_be_area": "outer (from the Be area)",
    "outer_radius": "outer",
}


def plot_shell(run: Run, out_path: str) -> str:
    """Shell collapse: this run's cells coloured by density at t_end, and the
    inner and outer radii against time (lagrange solid, remap dashed) with
    Howell & Ball's stopping radii and the paper's."""
    mesh_name = "shell_mesh_z0.csv"
    cells = run.table(mesh_name, CORNER_COLUMNS + ["density"])
    polys = slice_polygons(cells, run.path(mesh_name))
    # Constrained layout: the square map's title would meet the suptitle.
    fig, (ax_mesh, ax_r) = plt.subplots(1, 2, figsize=(13, 6.4), constrained_layout=True)
    art = draw_cells(ax_mesh, polys, cells["density"])
    fig.colorbar(art, ax=ax_mesh, label=LABELS["rho"], shrink=0.85)
    ax_mesh.autoscale_view()
    ax_mesh.set_aspect("equal")
    ax_mesh.set_xlabel(LABELS["x"])
    ax_mesh.set_ylabel(LABELS["y"])
    ax_mesh.set_title("Shell at t_end" if run.mode != "remap"
                      else "Density on the fixed mesh at t_end (shell in gas)")
    spare = iter(SPARE_COLOURS * 4)
    colours = dict(SHELL_RADIUS_COLOURS)
    for curve, radii in curve_tables(run, "shell_radii.csv", ["t"]):
        for column in radii:
            if column == "t" or "radius" not in column or radii[column].dtype.kind != "f":
                continue
            colour = colours.setdefault(column, next(spare))
            ax_r.plot(radii["t"], radii[column], ls=curve.style["ls"], color=colour, lw=1.2,
                      label=f"{curve.label}: {SHELL_RADIUS_WORDS.get(column, column)}")
    runs = [run] + ([run.partner] if run.partner is not None else [])
    for name, colour in (("stopping_inner_radius", "tab:blue"),
                         ("stopping_outer_radius", "tab:orange")):
        check = next((r.check(name) for r in runs if r.check(name)), None)
        if check and isinstance(check.get("reference"), (int, float)):
            ax_r.axhline(check["reference"], ls="-.", color=colour, lw=0.7,
                         label=f"Howell & Ball {1000 * check['reference']:.1f} mm")
        paper = paper_number(runs, name, "remap")
        if paper is not None:
            ax_r.axhline(paper, ls=(0, (1, 3)), color=colour, lw=0.9,
                         label=f"paper (remap) {1000 * paper:.0f} mm")
    ax_r.set_xlabel(LABELS["t"])
    ax_r.set_ylabel("radius [m]")
    ax_r.grid(alpha=0.3)
    # Below the axes: the radii curves fill the panel.
    ax_r.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize="small")
    fig.suptitle(pair_title(run, "Beryllium shell collapse"))
    return save(fig, out_path)


def plot_beam_tip(run: Run, out_path: str) -> str:
    """Oscillating plate: vertical tip displacement against time (paper
    Fig. 12), the lagrange run a curve and the remap run points, with the
    theoretical half period marked."""
    curves = curve_tables(run, "beam_tip.csv", ["t", "tip_displacement_y"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    ax.axhline(0.0, color="0.5", lw=0.6)
    for curve, t in curves:
        if curve.run.mode == "remap":
            # Points, as the paper: about 40 of them over the run.
            every = max(1, len(t["t"]) // 40)
            ax.plot(t["t"][::every], t["tip_displacement_y"][::every], "o", ms=4,
                    mfc="none", color=curve.style["color"], label=f"{curve.label} (points)")
        else:
            ax.plot(t["t"], t["tip_displacement_y"], lw=1.2, label=curve.label, **curve.style)
    check = run.check("half_period")
    if check and isinstance(check.get("reference"), (int, float)):
        ax.axvline(check["reference"], ls="-.", color="black", lw=0.8,
                   label=f"half period (Timoshenko) {1e6 * check['reference']:.2f} µs")
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("tip displacement y [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(pair_title(run, "Oscillating plate: tip displacement"))
    fig.tight_layout()
    return save(fig, out_path)


# --------------------------------------------------------------------------
# Generic plots (drawn for any problem whose run wrote the input file)
# --------------------------------------------------------------------------

def plot_radial(run: Run, out_path: str, field: str) -> str:
    """Scatter of one field against radius, one point per cell.

    Every cell is drawn (not a binned average) because the spread at a given
    radius is exactly what shows mesh imprinting and loss of symmetry.  The
    shock radius lines show at a glance whether the blast wave is where the
    similarity solution says and where the check measured it.
    """
    name = "radial.csv"
    t = run.table(name, ["r", field])
    r, v = t["r"], t[field]
    n = len(r)
    # Dense data needs faint points or the profile becomes a solid blob;
    # sparse data needs opaque ones to be visible at all.
    alpha = float(np.clip(10000.0 / max(n, 1), 0.1, 0.8))
    size = 4.0 if n < 5000 else 2.0 if n < 100000 else 1.0

    fig, ax = plt.subplots(figsize=(8, 5.5))
    ax.scatter(r, v, s=size, alpha=alpha, color="tab:blue", linewidths=0,
               rasterized=True)
    # Proxy handle: the real points are too faint to read in a legend.
    handles = [Line2D([], [], ls="", marker="o", ms=4, color="tab:blue",
                      label=f"cells ({n})")]
    # The exact solution at the same centroids (sedov's radial.csv carries it):
    # the curve the cells should lie on.
    exact = t.get(f"{field}_exact")
    if exact is not None and exact.dtype.kind == "f" and np.isfinite(exact).any():
        order = np.argsort(r)
        handles += ax.plot(r[order], exact[order], color="black", lw=1.0,
                           label="exact solution")

    shock = run.check("shock_radius")
    if shock:
        ref, val = shock.get("reference"), shock.get("value")
        if isinstance(ref, (int, float)):
            handles.append(ax.axvline(ref, color="black", ls="--", lw=1.2,
                                      label=f"reference shock radius "
                                            f"{fmt_num(ref, '.4g')} m"))
        if isinstance(val, (int, float)):
            handles.append(ax.axvline(val, color="tab:red", ls="-", lw=1.2,
                                      label=f"measured shock radius "
                                            f"{fmt_num(val, '.4g')} m"))

    ax.set_xlabel(LABELS["r"])
    ax.set_ylabel(LABELS[field])
    ax.set_xlim(left=0.0)
    ax.grid(alpha=0.3)
    ax.legend(handles=handles, loc="best", fontsize="small")
    ax.set_title(run_title(run, f"Radial {field_word(field)}"))
    fig.tight_layout()
    return save(fig, out_path)


def field_word(field: str) -> str:
    return {"rho": "density", "p": "pressure"}.get(field, field)


def triangulate_points(x: np.ndarray, y: np.ndarray) -> Triangulation:
    """Delaunay triangulation of cell centroids, minus spurious hull triangles.

    After mesh motion the slice need not be convex: Delaunay fills the convex
    hull, so a concave stretch of boundary gets bridged by triangles that
    paint colour where there is no cell.  Such a triangle is large compared
    with the cell spacing at its own corners, so hull triangles whose
    circumradius exceeds HULL_MASK_RATIO times the largest nearest-neighbour
    distance of their vertices are peeled off, repeatedly, from the outside
    in.  The test is local on purpose: a Lagrangian mesh has cells of very
    different sizes (Sedov's rarefied centre vs its compressed shell), and a
    global size threshold would cut away real, merely large, cells.
    Interior triangles are never masked.
    """
    tri = Triangulation(x, y)
    pts = np.column_stack([x, y])

    # Local cell spacing: distance from each centroid to its nearest neighbour.
    e = tri.edges
    edge_len = np.linalg.norm(pts[e[:, 0]] - pts[e[:, 1]], axis=1)
    spacing = np.full(len(x), np.inf)
    np.minimum.at(spacing, e[:, 0], edge_len)
    np.minimum.at(spacing, e[:, 1], edge_len)

    corners = pts[tri.triangles]                       # (ntri, 3, 2)
    a = np.linalg.norm(corners[:, 1] - corners[:, 2], axis=1)
    b = np.linalg.norm(corners[:, 2] - corners[:, 0], axis=1)
    c = np.linalg.norm(corners[:, 0] - corners[:, 1], axis=1)
    d1, d2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area2 = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])  # twice the area
    with np.errstate(divide="ignore", invalid="ignore"):
        circumradius = np.where(area2 > 0, a * b * c / (2.0 * area2), np.inf)
    too_big = circumradius > HULL_MASK_RATIO * spacing[tri.triangles].max(axis=1)

    mask = np.zeros(len(tri.triangles), dtype=bool)
    for _ in range(50):
        tri.set_mask(mask)
        peel = (tri.neighbors == -1).any(axis=1) & too_big & ~mask
        if not peel.any():
            break
        mask |= peel
    if mask.all():      # nothing sensible left: show the raw triangulation
        mask[:] = False
    tri.set_mask(mask)
    return tri


# Optional slice_z.csv columns: corners of each cell's bottom face, in order
# around the face, so the moved cells can be drawn as they are.
CORNER_COLUMNS = ["x0", "y0", "x1", "y1", "x2", "y2", "x3", "y3"]


def slice_polygons(table: Dict[str, np.ndarray], path: str) -> Optional[np.ndarray]:
    """The cells' corner quadrilaterals as an (n, 4, 2) array, or None.

    None when the slice has no corner columns (centroid-only output), so the
    caller falls back to triangulating centroids; a partial set of corner
    columns means writer and reader disagree and is reported, not guessed.
    """
    present = [c for c in CORNER_COLUMNS if c in table]
    if not present:
        return None
    missing = [c for c in CORNER_COLUMNS if c not in table]
    if missing:
        raise InputError(f"{os.path.basename(path)}: has corner columns but "
                         f"lacks {', '.join(missing)}")
    return np.stack([np.column_stack([table[f"x{k}"], table[f"y{k}"]])
                     for k in range(4)], axis=1)


def draw_cells(ax, polys: np.ndarray, values: np.ndarray, cmap: str = "viridis",
               limits: Optional[Tuple[float, float]] = None) -> PolyCollection:
    """Fill each cell quadrilateral with its (cell-constant) value.

    This shows the data exactly as the scheme holds it: no interpolation
    across the strongly stretched cells of a Lagrangian mesh, and no holes
    where centroids are far apart.

    The cells are filled twice, with no stroke, so no cell is enlarged (a
    widening stroke would hide the 1-2 pixel wide compressed shells): first
    without anti-aliasing, which tiles the plane with no gap, then with it on
    top, which smooths the outer boundary.  Anti-aliasing alone leaves light
    seams of background wherever two cells meet mid-pixel; the aliased layer
    alone gives a ragged boundary.  Snapping is off because matplotlib snaps
    only axis-aligned paths to pixel centres, which would shift undisturbed
    rectangular cells by up to half a pixel against their deformed
    neighbours.  Outlines are drawn only while there are few enough cells for
    them to be seen (beyond that they would turn the map grey), as a separate
    unfilled overlay so every edge looks alike.
    """
    finite = values[np.isfinite(values)]
    fill = None
    for antialiased in (False, True):
        layer = PolyCollection(polys, array=values, cmap=cmap,
                               closed=True, edgecolors="none", linewidths=0.0,
                               antialiaseds=antialiased, snap=False)
        if limits is not None:
            layer.set_clim(*limits)
        elif finite.size:
            layer.set_clim(finite.min(), finite.max())
        ax.add_collection(layer)
        fill = fill or layer
    if len(polys) < 2000:
        ax.add_collection(PolyCollection(
            polys, closed=True, facecolors="none",
            edgecolors=(0.0, 0.0, 0.0, 0.3), linewidths=0.3, snap=False))
    return fill


def plot_slice_fields(run: Run, out_path: str) -> str:
    """Density and pressure maps of the cell layer nearest z = 0.

    When the slice carries the corners of each cell's bottom face, every
    cell is drawn as its actual quadrilateral coloured by the cell value;
    otherwise (older output) a triangulation of the centroids is shaded.
    Either way no image grid is used, because after Lagrangian motion the
    cells are no longer on a lattice; equal aspect keeps circles circular,
    so asymmetry is real, not an artefact of the axes.
    """
    name = "slice_z.csv"
    fields = ["rho", "p"]
    t = run.table(name, ["x", "y"] + fields)
    x, y = t["x"], t["y"]
    polys = slice_polygons(t, run.path(name))

    keep = None
    tri = None
    if polys is not None:
        # A cell whose corners are not all finite cannot be drawn; keep the
        # rest rather than fail the figure.
        keep = np.isfinite(polys).all(axis=(1, 2))
        polys = polys[keep]
        if len(polys) == 0:
            raise InputError(f"{name}: no cell with finite corner coordinates")
    else:
        try:
            tri = triangulate_points(x, y)
        except (ValueError, RuntimeError):
            tri = None  # fewer than 3 points or all collinear: scatter below

    fig, axes = plt.subplots(1, 2, figsize=(12, 5.4))
    for ax, field in zip(axes, fields):
        v = t[field]
        if polys is not None:
            art = draw_cells(ax, polys, v[keep])
        elif tri is not None:
            art = ax.tripcolor(tri, v, shading="gouraud", cmap="viridis")
        else:
            art = ax.scatter(x, y, c=v, s=12, cmap="viridis")
        fig.colorbar(art, ax=ax, label=LABELS[field], shrink=0.9)
        ax.set_aspect("equal")
        ax.set_xlabel(LABELS["x"])
        ax.set_ylabel(LABELS["y"])
        ax.set_title(field_word(field).capitalize())
    if polys is not None:
        # add_collection does not autoscale: frame the mesh with a 2 % margin.
        lo = polys.reshape(-1, 2).min(axis=0)
        hi = polys.reshape(-1, 2).max(axis=0)
        pad = 0.02 * max(float((hi - lo).max()), 1e-300)
        for ax in axes:
            ax.set_xlim(lo[0] - pad, hi[0] + pad)
            ax.set_ylim(lo[1] - pad, hi[1] + pad)
    fig.suptitle(run_title(run, f"Slice nearest z = 0 ({len(x)} cells)"))
    fig.tight_layout()
    return save(fig, out_path)


def relative_drift(q: np.ndarray) -> Tuple[np.ndarray, bool]:
    """(q - q0) / |q0|, or q - q0 if q0 is 0; the flag says which.

    Relative drift is what is comparable between problems of different
    scale; a zero initial value (possible for a quantity the C++ side adds
    later) would make it undefined, so fall back to the absolute drift.
    """
    q0 = q[0]
    if q0 != 0 and math.isfinite(q0):
        return (q - q0) / abs(q0), True
    return q - q0, False


def plot_history(run: Run, out_path: str) -> str:
    """Time step per reason, and conservation drift, over the run.

    The top panel shows which limiter controls Δt when (a run stuck on
    'volume' or 'growth' points at a problem); the bottom one shows the
    drift of total energy and mass, which a Lagrangian scheme should keep at
    round-off.  Symlog keeps exact zeros (mass in pure Lagrange mode) and
    the sign of the drift visible while still spanning many decades.
    """
    name = "history.csv"
    t = run.table(name, ["t", "dt", "dt_reason", "mass", "total_energy"])
    time, dt = t["t"], t["dt"]
    reasons = np.array([str(r).strip() for r in t["dt_reason"]])

    fig, (ax_dt, ax_drift) = plt.subplots(2, 1, figsize=(9, 8), sharex=True)

    ax_dt.plot(time, dt, "-", color="0.75", lw=0.8, zorder=1)
    spare = iter(SPARE_COLOURS * 10)
    # Legend in order of first appearance, which reads as the run's story.
    for reason in dict.fromkeys(reasons):
        sel = reasons == reason
        count = int(sel.sum())
        colour = DT_REASON_COLOURS.get(reason) or next(spare)
        ax_dt.scatter(time[sel], dt[sel], s=10, color=colour, zorder=2,
                      label=f"{reason} ({count} step{'s' if count != 1 else ''})")
    if np.any(dt > 0):
        ax_dt.set_yscale("log")
    ax_dt.set_ylabel(LABELS["dt"])
    ax_dt.grid(alpha=0.3, which="major")
    ax_dt.legend(title="Δt limited by", fontsize="small", loc="best")
    ax_dt.set_title("Time step")

    all_relative = True
    for field, label, colour in (("total_energy", "total energy", "tab:red"),
                                 ("mass", "mass", "tab:blue")):
        drift, relative = relative_drift(t[field])
        all_relative &= relative
        kind = "" if relative else ", absolute"
        ax_drift.plot(time, drift, "-", lw=1.2, color=colour,
                      label=f"{label} (final {drift[-1]:+.2e}{kind})")
    # Below ~1e-16 relative drift is round-off: plot that band linearly.
    ax_drift.set_yscale("symlog", linthresh=1e-16, linscale=0.5)
    ax_drift.yaxis.set_minor_locator(
        SymmetricalLogLocator(base=10, linthresh=1e-16, subs=range(2, 10)))
    ax_drift.axhline(0.0, color="0.5", lw=0.6)
    ax_drift.set_xlabel(LABELS["t"])
    ax_drift.set_ylabel("relative drift (q − q₀)/|q₀|" if all_relative
                        else "drift q − q₀")
    ax_drift.grid(alpha=0.3, which="major")
    ax_drift.legend(fontsize="small", loc="best")
    ax_drift.set_title("Conservation drift")

    s = run.summary
    title = run_title(run, "History")
    perf = []
    if "steps" in s:
        perf.append(f"{s['steps']} steps")
    if "wall_seconds" in s:
        perf.append(f"wall {fmt_num(s['wall_seconds'])} s")
    total = (s.get("cell_steps_per_second") or {}).get("total") \
        if isinstance(s.get("cell_steps_per_second"), dict) else None
    if total is not None:
        perf.append(f"{fmt_num(total, '.3e')} cell-steps/s")
    if perf:
        title += "\n" + ", ".join(perf)
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)


# --------------------------------------------------------------------------
# HDF5 snapshots (fields.xmf + fields_NNNNN.h5, src/io/snapshot_writer.hpp)
# --------------------------------------------------------------------------

def import_h5py():
    """h5py, or None: the maps are skipped with a note when it is missing."""
    try:
        import h5py  # noqa: F401  (Debian: python3-h5py)
    except ImportError:
        return None
    return h5py


def list_snapshots(directory: str, shape: Tuple[Optional[int], Optional[int]]) -> List["Snapshot"]:
    """The snapshots of fields.xmf in time order.

    The series file is the authority: a new run rewrites the series from
    index 0, so fields_*.h5 files of an older, longer run in the same
    directory may remain and must not be taken.  Without fields.xmf the
    .h5 files are taken in name order.
    """
    series = os.path.join(directory, "fields.xmf")
    entries: List[Tuple[float, str]] = []
    if os.path.isfile(series):
        try:
            root = ET.parse(series).getroot()
        except ET.ParseError as exc:
            raise InputError(f"fields.xmf: not XML ({exc})")
        for grid in root.iter("Grid"):
            if grid.get("GridType") != "Uniform":
                continue
            time = grid.find("Time")
            item = grid.find("Topology/DataItem")
            if time is None or item is None or not item.text:
                continue
            name = item.text.strip().split(":")[0]
            entries.append((float(time.get("Value", "nan")), os.path.join(directory, name)))
    else:
        for path in sorted(glob.glob(os.path.join(directory, "fields_[0-9]*.h5"))):
            entries.append((math.nan, path))
    return [Snapshot(path, time, shape) for time, path in entries if os.path.isfile(path)]


class Snapshot:
    """One HDF5 snapshot: mesh, fields read on demand, and the cell layer
    the maps show (the one nearest the mid-plane in z).  `shape` is the
    run's (mesh.nx, mesh.ny), which lets a block mesh's layer be read as a
    grid."""

    def __init__(self, path: str, time: float, shape: Tuple[Optional[int], Optional[int]]):
        self.path = path
        self.time = time
        self.shape = shape
        self._fields: Dict[str, np.ndarray] = {}
        self._names: Optional[List[str]] = None
        self._coords: Optional[np.ndarray] = None
        self._cells: Optional[np.ndarray] = None
        self._layer: Optional[np.ndarray] = None

    def _read_mesh(self) -> None:
        h5py = import_h5py()
        if h5py is None:
            raise SkipPlot("python3-h5py is not installed: no HDF5 snapshot can be read")
        try:
            with h5py.File(self.path, "r") as f:
                self._coords = np.asarray(f["mesh/coordinates"][...], dtype=float)
                self._cells = np.asarray(f["mesh/connectivity"][...], dtype=np.int64)
                self._names = list(f["fields"].keys()) if "fields" in f else []
                if math.isnan(self.time) and "time" in f.attrs:
                    self.time = float(f.attrs["time"])
        except (OSError, KeyError) as exc:
            raise InputError(f"{os.path.basename(self.path)}: {exc}")
        if self._cells.ndim != 2 or self._cells.shape[1] != 8 or \
                self._coords.ndim != 2 or self._coords.shape[1] != 3:
            raise InputError(f"{os.path.basename(self.path)}: mesh is not 8-node hexahedra in 3D")

    @property
    def coords(self) -> np.ndarray:
        if self._coords is None:
            self._read_mesh()
        return self._coords

    @property
    def cells(self) -> np.ndarray:
        if self._cells is None:
            self._read_mesh()
        return self._cells

    def has(self, name: str) -> bool:
        if self._names is None:
            self._read_mesh()
        return name in self._names

    def field(self, name: str) -> np.ndarray:
        """A cell field, e.g. density, pressure, volume_fraction_0."""
        if name not in self._fields:
            if not self.has(name):
                raise SkipPlot(f"{os.path.basename(self.path)} has no field '{name}'")
            with import_h5py().File(self.path, "r") as f:
                self._fields[name] = np.asarray(f["fields/" + name][...], dtype=float)
        return self._fields[name]

    @property
    def n_materials(self) -> int:
        """Materials with a volume fraction (1 for a single-material run,
        whose snapshots hold none)."""
        k = 0
        while self.has(f"volume_fraction_{k}"):
            k += 1
        return max(k, 1)

    def layer(self) -> np.ndarray:
        """Indices of the cells of the layer nearest the mesh's mid-plane in z
        (the only layer of a slab one cell thick), in cell order."""
        if self._layer is None:
            z = self.coords[self.cells][:, :, 2]
            z_c = z.mean(axis=1)
            z_mid = 0.5 * (self.coords[:, 2].min() + self.coords[:, 2].max())
            target = z_c[np.argmin(np.abs(z_c - z_mid))]
            thickness = np.median(np.abs(z[:, 4:].mean(axis=1) - z[:, :4].mean(axis=1)))
            self._layer = np.nonzero(np.abs(z_c - target) <= 0.25 * thickness)[0]
        return self._layer

    def layer_polygons(self) -> np.ndarray:
        """(n, 4, 2): the x-y corners of the layer's cells (their z-min face,
        VTK nodes 0-3 in order around it)."""
        return self.coords[self.cells[self.layer(), :4], :2]

    def outline_segments(self) -> np.ndarray:
        """(m, 2, 2): the layer's boundary edges, those of one cell only."""
        faces = self.cells[self.layer(), :4]
        edges = np.stack([faces, np.roll(faces, -1, axis=1)], axis=2).reshape(-1, 2)
        keys = np.sort(edges, axis=1)
        _, first, counts = np.unique(keys, axis=0, return_index=True, return_counts=True)
        boundary = edges[first[counts == 1]]
        return self.coords[boundary][:, :, :2]

    def grid(self) -> Optional[np.ndarray]:
        """The layer's cells as an (ny, nx) array of cell indices when they
        form a structured block (cell (j, i + 1) shares the edge 1-2 of cell
        (j, i), cell (j + 1, i) the edge 3-2), else None."""
        cells = self.layer()
        nx, ny = self.shape
        if not nx or not ny or len(cells) != nx * ny:
            return None
        block = cells.reshape(ny, nx)
        nodes = self.cells[block]  # (ny, nx, 8)
        if nx > 1 and not (np.array_equal(nodes[:, 1:, 0], nodes[:, :-1, 1]) and
                           np.array_equal(nodes[:, 1:, 3], nodes[:, :-1, 2])):
            return None
        if ny > 1 and not (np.array_equal(nodes[1:, :, 0], nodes[:-1, :, 3]) and
                           np.array_equal(nodes[1:, :, 1], nodes[:-1, :, 2])):
            return None
        return block

    def solid_extent(self, materials: List[int]) -> Optional[np.ndarray]:
        """x-y corners of the layer's cells holding more than half of one of
        `materials` (what a view of the solids must show)."""
        layer = self.layer()
        keep = np.zeros(len(layer), dtype=bool)
        for k in materials:
            keep |= self.field(f"volume_fraction_{k}")[layer] > 0.5
        return self.layer_polygons()[keep].reshape(-1, 2) if keep.any() else None


def padded_grid(snapshot: Snapshot, block: np.ndarray, values: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centre-of-face points of a structured layer, one ring wider: the
    boundary faces' midpoints (and corner nodes) carry the boundary cell's
    value, the mirror ghost of a wall, so a contour reaches the boundary
    instead of stopping half a cell short."""
    p = snapshot.coords[:, :2]
    q = [p[snapshot.cells[block, n]] for n in range(4)]  # (ny, nx, 2) each
    ny, nx = block.shape
    g = np.empty((ny + 2, nx + 2, 2))
    g[1:-1, 1:-1] = 0.25 * (q[0] + q[1] + q[2] + q[3])
    g[1:-1, 0] = 0.5 * (q[0] + q[3])[:, 0]
    g[1:-1, -1] = 0.5 * (q[1] + q[2])[:, -1]
    g[0, 1:-1] = 0.5 * (q[0] + q[1])[0, :]
    g[-1, 1:-1] = 0.5 * (q[3] + q[2])[-1, :]
    g[0, 0], g[0, -1] = q[0][0, 0], q[1][0, -1]
    g[-1, 0], g[-1, -1] = q[3][-1, 0], q[2][-1, -1]
    v = np.pad(values[block], 1, mode="edge")
    return g[..., 0], g[..., 1], v


def draw_alpha_contour(ax, snapshot: Snapshot, material: int, **style) -> None:
    """The alpha = 0.5 contour of `material` on the snapshot's layer.

    On a structured layer (every remap mesh, and the lagrange block meshes)
    the contour is drawn on the grid of cell centres padded to the
    boundary; otherwise on a triangulation of the cell centres."""
    alpha = snapshot.field(f"volume_fraction_{material}")
    layer = snapshot.layer()
    if not ((alpha[layer] > 0.5).any() and (alpha[layer] < 0.5).any()):
        return  # no interface in this layer
    effects = style.pop("path_effects", None)
    block = snapshot.grid()
    if block is not None:
        x, y, v = padded_grid(snapshot, block, alpha)
        contours = ax.contour(x, y, v, levels=[0.5], **style)
    else:
        centres = snapshot.layer_polygons().mean(axis=1)
        tri = triangulate_points(centres[:, 0], centres[:, 1])
        contours = ax.tricontour(tri, alpha[layer], levels=[0.5], **style)
    if effects:
        for line in contours.collections:
            line.set_path_effects(effects)


# Colours of the alpha = 0.5 contours on the field maps, one per solid.
CONTOUR_COLOURS = ["white", "magenta", "cyan", "yellow"]


def maps_apply(run: Run) -> bool:
    """Field maps are drawn for 2D runs (a slab one cell thick, at least
    4 x 4 cells), for multi-material runs with at least 4 x 4 cells in the
    plane (their interfaces are the point) and for the beam (the paper shows
    its fields); not for 1D bars (a strip of cells says less than
    `wilkins_profiles.png`) or single-material 3D blocks, whose slice says
    little."""
    if run.problem == "beam":
        return True
    nx, ny, nz = (run.config_int(f"mesh.n{a}") for a in "xyz")
    planar = bool(nx) and bool(ny) and min(nx, ny) >= 4
    if isinstance(run.summary.get("interfaces"), dict):
        return planar
    return nz == 1 and planar


def final_snapshot(run: Run) -> Snapshot:
    snaps = run.snapshots()
    if not snaps:
        raise SkipPlot(f"{run.dir}: fields.xmf lists no snapshot file")
    return snaps[-1]


def draw_field_map(fig, ax, run: Run, snap: Snapshot, field: str,
                   limits: Optional[Tuple[float, float]] = None, colorbar: bool = True):
    """One field of a snapshot's layer, cell by cell, with the alpha = 0.5
    contour of each solid material on top; returns the legend handles."""
    polys = snap.layer_polygons()
    values = snap.field(field)[snap.layer()]
    cmap = "viridis"
    if field == "pressure":
        # Compression and tension on either side of white (zero pressure).
        top = max(abs(v) for v in limits) if limits else float(np.nanmax(np.abs(values)))
        cmap, limits = "RdBu_r", (-top, top)
    art = draw_cells(ax, polys, values, cmap=cmap, limits=limits)
    if colorbar:
        fig.colorbar(art, ax=ax, label=LABELS["rho" if field == "density" else "p"], shrink=0.9)
    handles = []
    if snap.n_materials > 1:
        for i, k in enumerate(run.solid_materials(snap)):
            colour = CONTOUR_COLOURS[i % len(CONTOUR_COLOURS)]
            # A dark edge keeps a light line visible on light cells (the
            # solid's density, the gas's near-zero pressure).
            halo = [patheffects.withStroke(linewidth=2.6, foreground="black")]
            draw_alpha_contour(ax, snap, k, colors=colour, linewidths=1.2, path_effects=halo)
            handles.append(Line2D([], [], color=colour, lw=1.2, path_effects=halo,
                                  label=f"α = 0.5, material {k} (solid)"))
    lo, hi = polys.reshape(-1, 2).min(axis=0), polys.reshape(-1, 2).max(axis=0)
    pad = 0.02 * max(float((hi - lo).max()), 1e-300)
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(LABELS["x"])
    ax.set_ylabel(LABELS["y"])
    return handles


def snapshot_words(run: Run, snap: Snapshot) -> str:
    """'Fields at t_end' for the final state (the title's run line gives
    t_end), else the snapshot's time."""
    t_end = run.summary.get("t_end")
    if isinstance(t_end, (int, float)) and abs(snap.time - t_end) <= 1e-9 * abs(t_end):
        return "Fields at t_end"
    return f"Fields at t = {fmt_num(snap.time)} s"


def layer_words(snap: Snapshot) -> str:
    z = snap.coords[snap.cells[snap.layer()]][:, :, 2].mean()
    thick = snap.coords[:, 2].max() - snap.coords[:, 2].min()
    layers = len(snap.cells) // max(len(snap.layer()), 1)
    return "" if layers <= 1 else f", cell layer at z = {z:.3g} m of {thick:.3g} m"


def plot_field_maps(run: Run, out_path: str) -> str:
    """Density and pressure of the final state on the cells of one layer
    (the slab of a 2D run), with each solid's alpha = 0.5 contour: the
    paper's field figures."""
    snap = final_snapshot(run)
    polys = snap.layer_polygons()
    extent = polys.reshape(-1, 2).max(axis=0) - polys.reshape(-1, 2).min(axis=0)
    wide = extent[0] > 1.5 * extent[1]
    # Wide domains stacked, each map about 8 inches wide plus its colour bar.
    aspect = float(extent[0] / max(extent[1], 1e-300))
    fig, axes = plt.subplots(2 if wide else 1, 1 if wide else 2,
                             figsize=(11, min(8.5, 2.0 + 16.0 / aspect)) if wide else (13, 5.6))
    handles = []
    for ax, field in zip(axes, ("density", "pressure")):
        handles = draw_field_map(fig, ax, run, snap, field) or handles
        ax.set_title(("Density" if field == "density" else "Pressure")
                     + (" (mixture)" if snap.n_materials > 1 else ""))
    if handles:
        axes[0].legend(handles=handles, loc="upper right", fontsize="small", framealpha=0.8)
    fig.suptitle(run_title(run, snapshot_words(run, snap)) + layer_words(snap))
    fig.tight_layout()
    return save(fig, out_path)


def plot_fields_vs_lagrange(run: Run, out_path: str) -> Optional[str]:
    """The remap run's final density and pressure beside its lagrange
    partner's, each field on one colour scale (the lagrange run's range, as
    the paper's figures share theirs): a remap cell outside it saturates.
    scripts/compare_fields.py puts numbers on the difference.  Drawn for a
    remap run with a lagrange partner."""
    partner = run.partner
    if run.mode != "remap" or partner is None or partner.mode != "lagrange":
        return None
    snaps = {"lagrange": final_snapshot(partner), "remap": final_snapshot(run)}
    fig, axes = plt.subplots(2, 2, figsize=(13, 8.5), constrained_layout=True)
    handles = []
    for row, field in enumerate(("density", "pressure")):
        lagrange_values = snaps["lagrange"].field(field)[snaps["lagrange"].layer()]
        limits = (float(np.nanmin(lagrange_values)), float(np.nanmax(lagrange_values)))
        if field == "density":  # (the gas of the remap run: down to zero)
            limits = (0.0, limits[1])
        for col, (mode, owner) in enumerate((("lagrange", partner), ("remap", run))):
            ax = axes[row][col]
            handles = draw_field_map(fig, ax, owner, snaps[mode], field, limits,
                                     colorbar=(col == 1)) or handles
            ax.set_title(f"{mode}: {field_word('rho' if field == 'density' else 'p')}")
    if handles:
        axes[0][1].legend(handles=handles, loc="upper right", fontsize="small", framealpha=0.8)
    fig.suptitle(run_title(run, "Final fields, lagrange and remap on one colour scale each"))
    return save(fig, out_path)


def plot_density_snapshots(run: Run, out_path: str) -> Optional[str]:
    """Density at the run's snapshot times (initial, requested, final; at most
    six, evenly picked), one colour scale, solid contours on top: the paper's
    time series (ball Fig. 14, beam).  Not drawn for two snapshots or fewer
    (initial and final only: fields_map.png shows the final one)."""
    snaps = run.snapshots()
    if len(snaps) < 3:
        return None
    picks = sorted(set(np.linspace(0, len(snaps) - 1, min(6, len(snaps))).round().astype(int)))
    chosen = [snaps[i] for i in picks]
    values = np.concatenate([s.field("density")[s.layer()] for s in chosen])
    limits = (float(np.nanmin(values)), float(np.nanmax(values)))
    cols = min(3, len(chosen))
    rows = (len(chosen) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5 * cols, 4.2 * rows), squeeze=False,
                             constrained_layout=True)
    handles = []
    mappable = None
    for ax, snap in zip(axes.flat, chosen):
        handles = draw_field_map(fig, ax, run, snap, "density", limits, colorbar=False) or handles
        mappable = mappable or ax.collections[0]
        ax.set_title(f"t = {fmt_num(snap.time)} s")
    for ax in list(axes.flat)[len(chosen):]:
        ax.set_visible(False)
    fig.colorbar(mappable, ax=[a for a in axes.flat if a.get_visible()],
                 label=LABELS["rho"], shrink=0.9)
    if handles:
        axes.flat[0].legend(handles=handles, loc="upper right", fontsize="small", framealpha=0.8)
    fig.suptitle(run_title(run, "Density at the snapshot times") + layer_words(chosen[-1]))
    return save(fig, out_path)


# --------------------------------------------------------------------------
# Comparison table
# --------------------------------------------------------------------------

def comparison_rows(run: Run) -> List[List[str]]:
    """One row per check of the remap run: its value and reference, the
    lagrange run's value, the lagrange reference and the paper's number."""
    curves = {c.run.mode: c.run for c in overlay_runs(run)}
    remap, lagrange = curves.get("remap"), curves.get("lagrange")
    if remap is None or lagrange is None:
        return []
    rows = []
    for name, check in (remap.summary.get("checks") or {}).items():
        if not isinstance(check, dict):
            continue
        ours = lagrange.check(name) or {}
        numbers = (check.get("value"), check.get("reference"), ours.get("value"),
                   check.get("lagrange_reference"), check.get("paper"))
        verdict = ("n/a" if check.get("applies") is False
                   else {True: "pass", False: "FAIL"}.get(check.get("pass"), "?"))
        if check.get("source"):
            verdict += f" ({check['source']})"
        rows.append([name] + [fmt_num(v, ".5g", "–") for v in numbers] + [verdict])
    return rows


def write_comparison(run: Run, out_dir: str) -> Optional[str]:
    """comparison.md: the remap checks next to the lagrange run's (a
    Markdown table; '–' where a run or the paper gives no number)."""
    rows = comparison_rows(run)
    if not rows:
        return None
    header = ["check", "remap", "remap reference", "lagrange (this pair)",
              "lagrange reference", "paper", "remap check"]
    lines = [f"{run.problem}: remap {run.summary.get('cells', '?')} cells vs lagrange "
             f"{run.partner.summary.get('cells', '?')} cells, t = {fmt_num(run.summary.get('t_end'))} s",
             "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "comparison.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


# --------------------------------------------------------------------------
# Dispatch
# --------------------------------------------------------------------------

def always(run: Run) -> bool:
    return True


@dataclass(frozen=True)
class Plot:
    """One output figure: its file name, the input it needs, how to draw it,
    and whether it applies to a run (checked before its input is read)."""
    output: str
    source: str
    draw: Callable[[Run, str], Optional[str]]
    applies: Callable[[Run], bool] = always


# Plots that only make sense for one problem, keyed by summary["problem"].
PROBLEM_PLOTS: Dict[str, List[Plot]] = {
    "sod": [Plot("sod_profiles.png", "sod_profile.csv", plot_sod_profiles)],
    "wilkins": [Plot("wilkins_profiles.png", "wilkins_profile.csv", plot_wilkins_profiles)],
    "pile": [Plot("pile_wall_stress.png", "pile_wall_stress.csv", plot_pile_wall_stress)],
    "taylor": [Plot("taylor.png", "taylor_mesh_z0.csv", plot_taylor),
               Plot("taylor_outline.png", "fields.xmf", plot_taylor_outline)],
    "shell": [Plot("shell.png", "shell_mesh_z0.csv", plot_shell)],
    "beam": [Plot("beam_tip.png", "beam_tip.csv", plot_beam_tip)],
    "rod": [Plot("rod.png", "rod_plane_z0.csv", plot_rod)],
}

# Plots drawn for any problem, as long as the run wrote their input: radial
# output is written by every radially symmetric problem (sedov, noh, ...) and
# the slice by every 3D one, so keying them on the file keeps new problems
# plotted without touching this script.
GENERIC_PLOTS: List[Plot] = [
    Plot("radial_density.png", "radial.csv", partial(plot_radial, field="rho")),
    Plot("radial_pressure.png", "radial.csv", partial(plot_radial, field="p")),
    Plot("slice_fields.png", "slice_z.csv", plot_slice_fields),
    Plot("fields_map.png", "fields.xmf", plot_field_maps, maps_apply),
    Plot("fields_vs_lagrange.png", "fields.xmf", plot_fields_vs_lagrange, maps_apply),
    Plot("density_snapshots.png", "fields.xmf", plot_density_snapshots, maps_apply),
    Plot("history.png", "history.csv", plot_history),
]


def plots_for(run: Run) -> List[Plot]:
    """The candidate plots for this run: problem-specific first, then generic."""
    return PROBLEM_PLOTS.get(run.problem, []) + GENERIC_PLOTS


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
