"""Field maps from the HDF5 snapshots: density and pressure on one cell
layer with each solid's alpha = 0.5 contour (the final state, remap beside
lagrange, the snapshot times)."""

from typing import Optional, Tuple

import numpy as np
import matplotlib.pyplot as plt
from matplotlib import patheffects
from matplotlib.lines import Line2D

from .cells import draw_cells, triangulate_points
from .errors import SkipPlot
from .figure import LABELS, field_word, fmt_num, run_title, save
from .readers import Run
from .snapshots import Snapshot


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
