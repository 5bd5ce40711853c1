"""Per-problem figures of deformed solids: the taylor bar (density map,
length against time, outline at t_end), the 3D rod (profile, plastic
strain, length) and the beryllium shell (density map, radii)."""

from typing import Dict, List, Optional, Tuple

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D

from .cells import CORNER_COLUMNS, draw_cells, slice_polygons
from .errors import InputError, note
from .fields import draw_alpha_contour
from .figure import LABELS, SPARE_COLOURS, save
from .pairing import curve_tables, overlay_runs, pair_title
from .readers import Run


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
