"""Cell data on a plane: the cells' corner quadrilaterals from a CSV, a
masked triangulation of cell centroids, draw_cells, and the slice_z.csv
maps drawn with them."""

import os
from typing import Dict, Optional, Tuple

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
from matplotlib.tri import Triangulation

from .errors import InputError
from .figure import LABELS, field_word, run_title, save
from .readers import Run


# Slice maps: a hull triangle is taken as bridging a gap (not covering cells)
# when its circumradius exceeds this many local cell spacings; see
# triangulate_points.  A right triangle over a single missing cell has ~0.7,
# a well-shaped one between stretched cells 2-3.
HULL_MASK_RATIO = 5.0


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
