"""Renders a `rod` run's last snapshot in 3D with ParaView: the quarter rod
coloured by its equivalent plastic strain, seen from beyond the wall so that
the impact face and the mushroom show (docs/verification.md §8.10).

    pvpython scripts/paraview_rod.py OUTPUT_DIR        # writes OUTPUT_DIR/rod_3d.png
    xvfb-run -a pvpython scripts/paraview_rod.py DIR   # on a machine without a display

Needs ParaView's pvpython (Debian: paraview); lagremap itself does not.
"""
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, SaveScreenshot, Show,
                             XDMFReader)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: pvpython scripts/paraview_rod.py OUTPUT_DIR")
    out = sys.argv[1]
    series = os.path.join(out, "fields.xmf")
    if not os.path.isfile(series):
        sys.exit(f"paraview_rod: no {series} (a rod run's output directory?)")
    reader = XDMFReader(FileNames=[series])
    times = reader.TimestepValues
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [1200, 700]
    view.ViewTime = times[-1] if times else 0.0
    display = Show(reader, view)
    ColorBy(display, ("CELLS", "plastic_strain"))
    display.RescaleTransferFunctionToDataRange(True)
    display.SetScalarBarVisibility(view, True)
    # from beyond the wall (x < 0), above the quarter's outer side
    view.CameraPosition = [-0.025, 0.03, 0.035]
    view.CameraFocalPoint = [0.008, 0.002, 0.002]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.ResetCamera()
    path = os.path.join(out, "rod_3d.png")
    SaveScreenshot(path, view, ImageResolution=[1200, 700])
    print(path)


if __name__ == "__main__":
    main()
