"""Reading a run directory: CSV tables into column arrays, summary.json,
and the Run object that caches a directory's tables and snapshots."""

import csv
import json
import os
from typing import Dict, List, Optional

import numpy as np

from .errors import InputError, fail
from .snapshots import Snapshot, list_snapshots


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
    overlays compare it with (set by plot.py's main, None when there is none).
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
