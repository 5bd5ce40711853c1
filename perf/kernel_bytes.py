#!/usr/bin/python3
"""Bytes each GPU kernel of a time step reads and writes per cell, and the
bandwidth bound of a step that follows from them.

Reads perf/kernel_views.txt (the Views each kernel of the staged form touches,
kept by hand from the kernels) and sizes every View by its shape (the table
VIEWS below: bytes per entity, and entities per cell for the run), so that
carved Views (RemapStep's shared work memory) count like labelled ones.

  perf/kernel_bytes.py taylor|sedov [--bandwidth TB/s] [--cells N]
    taylor: `taylor --mode remap` (220 x 80 x 1 slab: 2 materials, one solid,
            16 remapped columns, 2.03 nodes per cell)
    sedov:  `sedov` in lagrange mode at N cells of a cube (1 material, no solid)
    --bandwidth: the GPU's memory bandwidth (default 4.3 TB/s, an H200's
                 reachable share of its 4.8 TB/s peak)

Prints a markdown table, kernels in step order: launches per step, bytes
read and written per cell-step (over the launches), and the time per step
and the cell-steps per second that the bandwidth alone allows.
"""
import argparse
import math
import pathlib
import re
import sys

HERE = pathlib.Path(__file__).resolve().parent

# A run: materials M, remapped columns V, nodes per cell, whether it has solids.
RUNS = {
    "taylor": {"mode": "remap", "M": 2, "V": 16, "solids": True,
               "nodes_per_cell": (221 * 81 * 2) / (220 * 80), "cells": 220 * 80},
    "sedov": {"mode": "lagrange", "M": 1, "V": 7, "solids": False,
              "nodes_per_cell": None, "cells": 30 ** 3},
}

# Bytes of each View per entity, and its entity: cell, node or corner (8 a
# cell); materials M, columns V as above. Views of a few entries
# (the material table, the sides' kinds, the projectors) count as 0.
D, I = 8, 4  # a double, an int
VIEWS = {
    # mesh
    "mesh::cell_nodes": ("cell", 8 * I), "mesh::cell_neighbors": ("cell", 6 * I),
    "mesh::cell_face_side": ("cell", 6 * I), "mesh::cell_neighbor_face": ("cell", 6 * I),
    "mesh::cell_owned": ("cell", I), "mesh::x_n": ("node", 3 * D),
    "mesh::node_solve_order": ("node", I), "mesh::node_twin_source": ("node", I),
    "mesh::node_twin_flip": ("node", I), "mesh::node_twin_offsets": ("node", I),
    "mesh::node_twins": ("node", I), "mesh::node_corner_offsets": ("node", I),
    "mesh::node_corners": ("corner", I), "mesh::node_traction_offsets": ("node", I),
    "mesh::node_projector_id": ("node", I), "mesh::node_owned": ("node", I),
    "mesh::projectors": ("none", 0), "mesh::side_kind": ("none", 0),
    "state::materials": ("none", 0),
    # state: cells, materials, corners, nodes
    **{f"state::{name}": ("cell", D) for name in
       ("m_c", "E_c", "E_c0", "vol_c", "vol_c0", "rho_c", "e_c", "p_c", "aL_c", "aT_c",
        "len_c", "dvdt_c")},
    "state::v_c": ("cell", 3 * D), "state::v_c0": ("cell", 3 * D), "state::x_c": ("cell", 3 * D),
    "state::S_c": ("cell", 6 * D),
    **{f"state::{name}": ("cell", "M*8") for name in
       ("alpha_ck", "alpha_ck0", "m_ck", "m_ck0", "e_ck", "e_ck0", "p_ck", "p_ck0", "w_ck", "w_ck0",
        "eps_ck", "eps_ck0")},
    "state::S_ck": ("cell", "M*48"), "state::S_ck0": ("cell", "M*48"),
    "state::n_ck": ("cell", "M*24"),
    "state::A_cp": ("corner", 3 * D), "state::M_cp": ("corner", 6 * D),
    "state::B_cp": ("corner", 3 * D),
    **{f"state::{name}": ("node", 3 * D) for name in ("x_n0", "x_n_next", "v_n", "f_ext_n")},
    # the remap's work
    "remap::density": ("cell", "V*8"), "remap::primitive": ("cell", "V*8"),
    "remap::gradient": ("cell", "V*24"), "remap::reach": ("cell", D),
    "remap::integral": ("cell", "V*8"), "remap::source_range": ("cell", "M*32"),
    "remap::dvol_r": ("cell", 12 * D), "remap::moment_r": ("cell", 12 * 3 * D),
}


def view_bytes_per_cell(name, run):
    if name not in VIEWS:
        sys.exit(f"kernel_bytes: no size for View {name} (add it to VIEWS)")
    entity, size = VIEWS[name]
    if isinstance(size, str):
        size = eval(size, {}, {"M": run["M"], "V": run["V"]})
    per_cell = {"cell": 1.0, "node": run["nodes_per_cell"], "corner": 8.0, "none": 0.0}[entity]
    return size * per_cell


def parse(path):
    """Sections: label, modes, launches, reads and writes as (view, fraction)."""
    sections, current = [], None
    for raw in path.read_text().splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith("["):
            current = {"label": line.strip("[]"), "modes": [], "launches": 1,
                       "read": [], "write": []}
            sections.append(current)
            continue
        key, _, rest = line.partition(" ")
        if key == "mode":
            current["modes"] = rest.split()
        elif key == "launches":
            current["launches"] = int(rest)
        elif key in ("read", "write"):
            for item in rest.split():
                name, _, fraction = item.partition("*")
                current[key].append((name, float(fraction) if fraction else 1.0))
        else:
            sys.exit(f"kernel_bytes: unknown line '{raw}'")
    return sections


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run", choices=sorted(RUNS))
    parser.add_argument("--bandwidth", type=float, default=4.3, help="TB/s")
    parser.add_argument("--cells", type=int, help="cells of the step (default: the run's)")
    args = parser.parse_args()
    run = dict(RUNS[args.run])
    if args.cells:
        run["cells"] = args.cells
    if run["nodes_per_cell"] is None:  # a cube of n^3 cells
        n = round(run["cells"] ** (1.0 / 3.0))
        run["nodes_per_cell"] = (n + 1) ** 3 / n ** 3
    rows, total_read, total_written = [], 0.0, 0.0
    for section in parse(HERE / "kernel_views.txt"):
        if run["mode"] not in section["modes"]:
            continue
        if "solids" in section["modes"] and not run["solids"]:
            continue
        n = section["launches"]
        read = n * sum(f * view_bytes_per_cell(v, run) for v, f in section["read"])
        written = n * sum(f * view_bytes_per_cell(v, run) for v, f in section["write"])
        label = re.sub(r"^lagremap::", "", section["label"])
        rows.append((label, n, read, written))
        total_read += read
        total_written += written
    total = total_read + total_written
    seconds_per_cell_step = total / (args.bandwidth * 1e12)
    print(f"{args.run}: {run['cells']:,} cells, {run['nodes_per_cell']:.3f} nodes per cell, "
          f"bandwidth {args.bandwidth} TB/s\n")
    print("| kernel | launches | read [B/cell-step] | written [B/cell-step] | share |")
    print("|---|---:|---:|---:|---:|")
    for label, n, read, written in rows:
        print(f"| `{label}` | {n} | {read:,.0f} | {written:,.0f} | "
              f"{100 * (read + written) / total:.1f}% |")
    print(f"| **total** | | **{total_read:,.0f}** | **{total_written:,.0f}** | |")
    print(f"\nbandwidth bound: {total:,.0f} bytes per cell-step -> "
          f"{1e6 * seconds_per_cell_step * run['cells']:,.1f} us per step, "
          f"{1.0 / seconds_per_cell_step / 1e9:.2f} G cell-steps/s at most")
    return 0 if math.isfinite(total) else 1


if __name__ == "__main__":
    sys.exit(main())
