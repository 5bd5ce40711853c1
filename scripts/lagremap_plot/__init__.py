"""The figures of lagremap run directories: the package behind scripts/plot.py.

Modules, from input to figure:
    errors      the exceptions a plot raises, exit statuses, notes on stderr
    snapshots   HDF5 snapshots (fields.xmf + fields_NNNNN.h5)
    readers     CSV tables, summary.json, the Run a directory is read into
    figure      what every figure shares: DPI, axis labels, titles, save
    pairing     the lagrange run an overlay compares a remap run with,
                line styles and labels of the overlaid runs
    cells       cell data on a plane, and the slice_z.csv maps
    radial      radial.csv scatter against radius
    history     history.csv: time step and conservation drift
    fields      field maps from the snapshots, alpha = 0.5 contours
    curves      per-problem curves: sod, wilkins, pile, beam
    shapes      per-problem deformed solids: taylor, rod, shell
    comparison  comparison.md, the checks of a run pair side by side
    registry    which plots a run gets (output name, input, draw function)

matplotlib's Agg backend is chosen here, before any module imports pyplot,
so no plot needs a display (CI, ssh).
"""

import matplotlib

matplotlib.use("Agg")
