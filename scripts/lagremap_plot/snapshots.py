"""HDF5 snapshots (fields.xmf + fields_NNNNN.h5, src/io/snapshot_writer.hpp):
the series in time order, and one snapshot's mesh, fields and mid-plane
cell layer, read on demand (h5py is optional: without it the maps are
skipped with a note)."""

import glob
import math
import os
import xml.etree.ElementTree as ET
from typing import Dict, List, Optional, Tuple

import numpy as np

from .errors import InputError, SkipPlot


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
