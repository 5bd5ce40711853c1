#!/usr/bin/python3
"""Draw PNG figures from a lagremap run directory.

Usage:
    scripts/plot.py DIR [--out OUTDIR] [--show-list]

DIR is a lagremap output directory.  It must hold ``summary.json``; every
other input (history.csv, sod_profile.csv, radial.csv, slice_z.csv) is
optional, and a plot whose input is missing is skipped silently, so the
script works on partial runs, quick runs with output switched off, and
directories copied around without their large CSV files.

For every PNG written the script prints its path, one per line, on stdout,
so callers (CI, the regression scripts) can collect the figures without
knowing which ones a given problem produces.  ``--show-list`` prints the
plots this directory supports instead of drawing them.

Exit status: 0 on success; 1 if some input file was present but could not be
plotted (a warning names it on stderr, the other plots are still drawn);
2 if DIR does not exist or holds no readable summary.json.

All quantities are taken to be SI, because that is what the C++ code writes.
"""

import argparse
import csv
import json
import math
import os
import sys
from dataclasses import dataclass
from functools import partial
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np
import matplotlib

matplotlib.use("Agg")  # never needs a display: runs in CI and over ssh
import matplotlib.pyplot as plt  # noqa: E402  (must follow matplotlib.use)
from matplotlib.collections import PolyCollection  # noqa: E402
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
    """A run directory: its summary plus lazily read, cached CSV files.

    Caching matters because radial.csv (up to ~250k rows) feeds two figures
    and should be parsed once.
    """

    def __init__(self, directory: str, summary: dict):
        self.dir = directory
        self.summary = summary
        self._tables: Dict[str, Dict[str, np.ndarray]] = {}

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


def load_run(directory: str) -> Run:
    """Open DIR or exit 2 with a one-line message.

    summary.json is the marker of a lagremap run directory and carries the
    problem name that selects the plots, so without it nothing can be done.
    """
    if not os.path.isdir(directory):
        fail(f"{directory}: no such directory")
    summary_path = os.path.join(directory, "summary.json")
    if not os.path.isfile(summary_path):
        fail(f"{directory}: no summary.json (not a lagremap output directory?)")
    try:
        with open(summary_path) as f:
            summary = json.load(f)
    except (OSError, ValueError) as exc:
        fail(f"{summary_path}: unreadable: {' '.join(str(exc).split())}")
    if not isinstance(summary, dict):
        fail(f"{summary_path}: top level is not a JSON object")
    return Run(directory, summary)


def fail(message: str) -> None:
    """Print a one-line error and exit 2 (the documented bad-input status)."""
    print(f"plot.py: error: {message}", file=sys.stderr)
    sys.exit(EXIT_BAD_DIR)


# --------------------------------------------------------------------------
# Formatting helpers
# --------------------------------------------------------------------------

def fmt_num(value, spec: str = ".3g") -> str:
    """Format a number from JSON, tolerating absent or non-numeric values."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return format(value, spec)
    return "?"


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
    if "pass" in check:
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
    """Flyer plate: density, velocity and sigma_xx along x (paper Fig. 3).

    Dashed lines mark the exact plastic state and elastic precursor levels of
    the default impact, so the two-wave structure (precursor plateau ahead of
    the plastic shock) can be judged by eye.
    """
    name = "wilkins_profile.csv"
    fields = ["rho", "u", "sigma_xx"]
    t = run.table(name, ["x"] + fields)
    order = np.argsort(t["x"], kind="stable")
    x = t["x"][order]
    exact = {"rho": (2985.6, 2800.2), "u": (400.0, 35.2), "sigma_xx": (-6.637e9, -0.636e9)}
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    for ax, field in zip(axes, fields):
        ax.plot(x, t[field][order], "-o", ms=2, lw=0.8, color="tab:blue", label="lagrange")
        plastic, precursor = exact[field]
        ax.axhline(plastic, ls="--", lw=0.8, color="black", label="exact plastic state")
        ax.axhline(precursor, ls=":", lw=0.8, color="tab:red", label="exact elastic precursor")
        ax.set_ylabel(LABELS[field])
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel(LABELS["x"])
    fig.suptitle(run_title(run, "Wilkins flyer plate"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_pile_wall_stress(run: Run, out_path: str) -> str:
    """Pile driving: wall sigma_xx against time with the exact square wave.

    The exact linear-elastic answer is 0 / twice the imposed stress / 0 on
    [0, L/c] / [L/c, 3L/c] / [3L/c, 4L/c]; overshoot at the fronts and the
    arrival time are what to look at.
    """
    name = "pile_wall_stress.csv"
    t = run.table(name, ["t", "sigma_xx", "exact"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    ax.plot(t["t"], t["exact"], "-", color="black", lw=1.2, label="exact (linear elastic)")
    ax.plot(t["t"], t["sigma_xx"], "-", color="tab:blue", lw=1.0, label="lagrange")
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("wall stress σ_xx [Pa]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(run_title(run, "Pile driving: stress on the wall"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_taylor(run: Run, out_path: str) -> str:
    """Taylor impact: the deformed bar (cells coloured by density, the
    mushroom at the wall) and the bar length against time with the paper's
    final length."""
    mesh_name, length_name = "taylor_mesh_z0.csv", "taylor_length.csv"
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
    ax_bar.set_title("Deformed bar at t_end" if run.summary.get("mode") != "remap"
                     else "Density on the fixed mesh at t_end (bar in gas)")
    history = run.table(length_name, ["t", "length"])
    mode = run.summary.get("mode", "lagrange")
    remap = mode == "remap"
    ax_len.plot(history["t"], history["length"], "--" if remap else "-", color="tab:blue",
                label=mode + (" (aluminium volume along the axis)" if remap else ""))
    reference = run.check("final_length")
    if reference and isinstance(reference.get("reference"), (int, float)):
        ax_len.axhline(reference["reference"], ls=":", color="black",
                       label=f"paper ({mode}) {reference['reference']:g} m")
    ax_len.set_xlabel(LABELS["t"])
    ax_len.set_ylabel("bar length [m]")
    ax_len.grid(alpha=0.3)
    ax_len.legend(loc="best", fontsize="small")
    fig.suptitle(run_title(run, "Taylor impact"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_shell(run: Run, out_path: str) -> str:
    """Shell collapse: the deformed quarter shell coloured by density, and the
    inner and outer radii against time with Howell & Ball's stopping radii."""
    mesh_name, radii_name = "shell_mesh_z0.csv", "shell_radii.csv"
    cells = run.table(mesh_name, CORNER_COLUMNS + ["density"])
    polys = slice_polygons(cells, run.path(mesh_name))
    fig, (ax_mesh, ax_r) = plt.subplots(1, 2, figsize=(12, 5))
    art = draw_cells(ax_mesh, polys, cells["density"])
    fig.colorbar(art, ax=ax_mesh, label=LABELS["rho"], shrink=0.85)
    ax_mesh.autoscale_view()
    ax_mesh.set_aspect("equal")
    ax_mesh.set_xlabel(LABELS["x"])
    ax_mesh.set_ylabel(LABELS["y"])
    ax_mesh.set_title("Shell at t_end")
    radii = run.table(radii_name, ["t", "inner_radius", "outer_radius_incompressible"])
    ax_r.plot(radii["t"], radii["inner_radius"], "-", color="tab:blue", label="inner radius")
    ax_r.plot(radii["t"], radii["outer_radius_incompressible"], "-", color="tab:orange",
              label="outer radius (shell area conserved)")
    for name, colour in (("stopping_inner_radius", "tab:blue"),
                         ("stopping_outer_radius", "tab:orange")):
        check = run.check(name)
        if check and isinstance(check.get("reference"), (int, float)):
            ax_r.axhline(check["reference"], ls="--", color=colour, lw=0.8,
                         label=f"Howell & Ball {1000 * check['reference']:.1f} mm")
    ax_r.set_xlabel(LABELS["t"])
    ax_r.set_ylabel("radius [m]")
    ax_r.grid(alpha=0.3)
    ax_r.legend(loc="best", fontsize="small")
    fig.suptitle(run_title(run, "Beryllium shell collapse"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_beam_tip(run: Run, out_path: str) -> str:
    """Oscillating plate: vertical tip displacement against time (paper
    Fig. 12), with the theoretical half period marked."""
    t = run.table("beam_tip.csv", ["t", "tip_displacement_y"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    ax.plot(t["t"], t["tip_displacement_y"], "-", color="tab:blue", label="lagrange")
    ax.axhline(0.0, color="0.5", lw=0.6)
    check = run.check("half_period")
    if check and isinstance(check.get("reference"), (int, float)):
        ax.axvline(check["reference"], ls="--", color="black", lw=0.8,
                   label=f"half period (Timoshenko) {1e6 * check['reference']:.2f} us")
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("tip displacement y [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(run_title(run, "Oscillating plate: tip displacement"))
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


def draw_cells(ax, polys: np.ndarray, values: np.ndarray) -> PolyCollection:
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
        layer = PolyCollection(polys, array=values, cmap="viridis",
                               closed=True, edgecolors="none", linewidths=0.0,
                               antialiaseds=antialiased, snap=False)
        if finite.size:
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
# Dispatch
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class Plot:
    """One output figure: its file name, the input it needs, how to draw it."""
    output: str
    source: str
    draw: Callable[[Run, str], str]


# Plots that only make sense for one problem, keyed by summary["problem"].
PROBLEM_PLOTS: Dict[str, List[Plot]] = {
    "sod": [Plot("sod_profiles.png", "sod_profile.csv", plot_sod_profiles)],
    "wilkins": [Plot("wilkins_profiles.png", "wilkins_profile.csv", plot_wilkins_profiles)],
    "pile": [Plot("pile_wall_stress.png", "pile_wall_stress.csv", plot_pile_wall_stress)],
    "taylor": [Plot("taylor.png", "taylor_mesh_z0.csv", plot_taylor)],
    "shell": [Plot("shell.png", "shell_mesh_z0.csv", plot_shell)],
    "beam": [Plot("beam_tip.png", "beam_tip.csv", plot_beam_tip)],
}

# Plots drawn for any problem, as long as the run wrote their input: radial
# output is written by every radially symmetric problem (sedov, noh, ...) and
# the slice by every 3D one, so keying them on the file keeps new problems
# plotted without touching this script.
GENERIC_PLOTS: List[Plot] = [
    Plot("radial_density.png", "radial.csv", partial(plot_radial, field="rho")),
    Plot("radial_pressure.png", "radial.csv", partial(plot_radial, field="p")),
    Plot("slice_fields.png", "slice_z.csv", plot_slice_fields),
    Plot("history.png", "history.csv", plot_history),
]


def plots_for(run: Run) -> List[Plot]:
    """The candidate plots for this run: problem-specific first, then generic."""
    problem = str(run.summary.get("problem", ""))
    return PROBLEM_PLOTS.get(problem, []) + GENERIC_PLOTS


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        description="Draw PNG figures from a lagremap output directory; "
                    "prints the path of each PNG written.")
    parser.add_argument("dir", metavar="DIR", help="lagremap output directory")
    parser.add_argument("--out", metavar="OUTDIR",
                        help="write PNGs here instead of DIR (created if needed)")
    parser.add_argument("--show-list", action="store_true",
                        help="list the plots for DIR (output, input, whether "
                             "the input is present) and draw nothing")
    args = parser.parse_args(argv)

    run = load_run(args.dir)
    out_dir = args.out or args.dir
    candidates = plots_for(run)

    if args.show_list:
        for plot in candidates:
            state = "available" if run.has(plot.source) else "missing-input"
            print(f"{os.path.join(out_dir, plot.output)}\t{plot.source}\t{state}")
        return 0

    todo = [p for p in candidates if run.has(p.source)]
    if todo:
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as exc:
            fail(f"{out_dir}: cannot create output directory: {exc.strerror}")

    status = 0
    for plot in todo:
        try:
            written = plot.draw(run, os.path.join(out_dir, plot.output))
        except (InputError, OSError, ValueError) as exc:
            plt.close("all")
            print(f"plot.py: warning: {plot.output} skipped: {exc}",
                  file=sys.stderr)
            status = EXIT_PLOT_FAILED
            continue
        print(written, flush=True)
    return status


if __name__ == "__main__":
    sys.exit(main())
