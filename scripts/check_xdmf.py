"""Open an XDMF file with ParaView's readers and summarise what ParaView sees.

Usage:
    pvpython [--force-offscreen-rendering] scripts/check_xdmf.py FILE.xmf [--reader auto|xdmf3|xdmf2] [--all-times]

Opens FILE.xmf with the XDMF3 reader (Xdmf3ReaderS), falling back to the legacy XDMF2
reader (XDMFReader) if that one cannot be created or raises, updates the pipeline and prints, for
the first time step (or every time step with --all-times), the number of cells and points,
the cell types and every cell array with its per-component ranges.

Exit status: 0 if every checked time step has cells, 1 if one has none, 2 if the file
does not exist or no reader could open it.
"""
import argparse
import os
import sys

from paraview import servermanager
from paraview import simple

VTK_CELL_NAMES = {10: "tetra", 12: "hexahedron", 13: "wedge", 14: "pyramid"}


def timestep_values(reader):
    tv = reader.TimestepValues
    if tv is None:
        return []
    if isinstance(tv, (int, float)):  # a single time step comes back as a scalar
        return [float(tv)]
    return [float(t) for t in tv]


def open_reader(path, which):
    attempts = []
    if which in ("auto", "xdmf3"):
        attempts.append(("Xdmf3ReaderS", lambda: simple.Xdmf3ReaderS(FileName=[path])))
    if which in ("auto", "xdmf2"):
        attempts.append(("XDMFReader", lambda: simple.XDMFReader(FileNames=[path])))
    for name, make in attempts:
        try:
            reader = make()
            # Without an explicit time the XDMF3 reader returns an empty grid for a
            # temporal collection, so request the first time step (as the GUI does).
            reader.UpdatePipelineInformation()
            times = timestep_values(reader)
            if times:
                reader.UpdatePipeline(times[0])
            else:
                reader.UpdatePipeline()
        except Exception as exc:  # reader missing or parse failure: try the next one
            print("%s failed: %s" % (name, exc), file=sys.stderr)
            continue
        # A reader that parsed the file but found no cells is kept (and reported as an
        # error below): the legacy reader is not tried then, as it crashes on some such
        # files (e.g. an empty <Domain/>).
        return name, reader
    return None, None


def leaf_datasets(obj):
    """Yields the non-composite datasets inside obj (obj itself if it is not composite)."""
    if obj is None:
        return
    if obj.IsA("vtkCompositeDataSet"):
        it = obj.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            yield it.GetCurrentDataObject()
            it.GoToNextItem()
    else:
        yield obj


def cell_type_counts(reader):
    counts = {}
    for ds in leaf_datasets(servermanager.Fetch(reader)):
        if not hasattr(ds, "GetCellType"):
            continue
        for i in range(ds.GetNumberOfCells()):
            t = ds.GetCellType(i)
            counts[t] = counts.get(t, 0) + 1
    return counts


def summarise(reader, time):
    if time is None:
        reader.UpdatePipeline()
        print("time: (none)")
    else:
        reader.UpdatePipeline(time)
        print("time: %.17g" % time)
    info = reader.GetDataInformation()
    n_cells = info.GetNumberOfCells()
    print("  cells: %d  points: %d" % (n_cells, info.GetNumberOfPoints()))
    types = cell_type_counts(reader)
    print("  cell types: " + ", ".join(
        "%s=%d" % (VTK_CELL_NAMES.get(t, "vtk%d" % t), n) for t, n in sorted(types.items())))
    names = reader.CellData.keys()
    print("  cell arrays: %d" % len(names))
    for name in names:
        arr = reader.CellData[name]
        nc = arr.GetNumberOfComponents()
        comps = " ".join("[%.17g, %.17g]" % tuple(arr.GetRange(c)) for c in range(nc))
        extra = "" if nc == 1 else "  |magnitude| [%.17g, %.17g]" % tuple(arr.GetRange(-1))
        print("    %s (%d comp): %s%s" % (name, nc, comps, extra))
    return n_cells


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--reader", choices=("auto", "xdmf3", "xdmf2"), default="auto")
    parser.add_argument("--all-times", action="store_true", help="summarise every time step")
    args = parser.parse_args()

    path = os.path.abspath(args.file)
    if not os.path.isfile(path):
        print("no such file: %s" % path, file=sys.stderr)
        return 2
    name, reader = open_reader(path, args.reader)
    if reader is None:
        print("no XDMF reader could open %s" % path, file=sys.stderr)
        return 2

    times = timestep_values(reader)
    print("file: %s" % path)
    print("reader: %s" % name)
    print("time steps: %d %s" % (len(times), times))

    to_check = (times if args.all_times else times[:1]) or [None]
    ok = True
    for t in to_check:
        if summarise(reader, t) <= 0:
            ok = False
    if not ok:
        print("ERROR: a checked time step has no cells", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
