"""The final mesh of a run whose mesh moves (lagrange and ALE modes): the
cells of a plane drawn with their edges and coloured by their scaled
Jacobian, the mesh-quality measure the run reports (docs/method.md §8.4)."""

import numpy as np
import matplotlib.pyplot as plt

from .cells import CORNER_COLUMNS, slice_polygons
from .errors import InputError
from .fields import final_snapshot
from .figure import LABELS, run_title, save
from .readers import Run
from matplotlib.collections import PolyCollection


def quad_scaled_jacobian(polys: np.ndarray) -> np.ndarray:
    """Smallest corner scaled Jacobian of each quadrilateral of an (n, 4, 2)
    array: at corner k, (e1 x e2) / (|e1| |e2|) with e1 to the next corner
    and e2 to the previous one; 1 for right angles, <= 0 for a flat or
    inverted corner."""
    nxt = np.roll(polys, -1, axis=1) - polys
    prv = np.roll(polys, 1, axis=1) - polys
    cross = nxt[..., 0] * prv[..., 1] - nxt[..., 1] * prv[..., 0]
    lengths = np.linalg.norm(nxt, axis=2) * np.linalg.norm(prv, axis=2)
    with np.errstate(divide="ignore", invalid="ignore"):
        corner = np.where(lengths > 0, cross / lengths, 0.0)
    # the quads' orientation (counter-clockwise or not) is the writer's
    sign = np.sign(np.median(corner.min(axis=1)))
    return (sign if sign != 0 else 1.0) * corner.min(axis=1)


def not_remap(run: Run) -> bool:
    return run.mode != "remap"


# Problems whose own CSV holds the plane to draw (the symmetry plane z = 0);
# a slab's (one cell thick) mesh is drawn from the final snapshot, and a 3D
# block's from its slice_z.csv where it writes one (a deformed block's cells
# near the mid-plane are no plane).
CSV_MESH_PROBLEMS = ("taylor", "shell", "rod")


def snapshot_mesh_applies(run: Run) -> bool:
    return (not_remap(run) and run.problem not in CSV_MESH_PROBLEMS
            and run.config_int("mesh.nz") == 1)


def plot_mesh(run: Run, out_path: str, source: str) -> str:
    """The cells of `source` (a CSV of corner quadrilaterals) at t_end, edges
    drawn, each filled by its scaled Jacobian."""
    cells = run.table(source, CORNER_COLUMNS)
    polys = slice_polygons(cells, run.path(source))
    if polys is None:
        raise InputError(f"{source}: no corner columns to draw the mesh from")
    return draw_mesh(run, out_path, polys)


def plot_snapshot_mesh(run: Run, out_path: str) -> str:
    """The final snapshot's mid layer of cells, as plot_mesh draws a CSV's."""
    return draw_mesh(run, out_path, final_snapshot(run).layer_polygons())


def draw_mesh(run: Run, out_path: str, polys: np.ndarray) -> str:
    quality = quad_scaled_jacobian(polys)
    span = np.ptp(polys.reshape(-1, 2), axis=0)
    aspect = span[1] / max(span[0], 1e-300)  # (the axes keep x and y to scale)
    if aspect <= 1.0:
        width, height = 11.0, max(3.5, min(9.0, 9.0 * aspect + 1.5))
    else:
        width, height = max(7.5, min(11.0, 8.0 / aspect + 3.0)), 9.0
    fig, ax = plt.subplots(figsize=(width, height))
    art = PolyCollection(polys, array=quality, cmap="magma", edgecolor="black",
                         linewidth=0.15)
    art.set_clim(min(0.0, quality.min()), 1.0)
    ax.add_collection(art)
    fig.colorbar(art, ax=ax, label="scaled Jacobian of the cell (in this plane)", shrink=0.8)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel(LABELS["x"])
    ax.set_ylabel(LABELS["y"])
    ax.set_title(f"smallest scaled Jacobian in this plane: {quality.min():.3f}")
    fig.suptitle(run_title(run, "Final mesh"))
    fig.tight_layout()
    return save(fig, out_path)
