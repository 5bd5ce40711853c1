#!/usr/bin/python3
"""scripts/plot.py on tiny lagrange + remap run pairs (ctest, label quick).

Usage: test_plot.py LAGREMAP_EXE PLOT_PY

Runs wilkins in both modes at half resolution and a coarse, short taylor in
both modes at the same cell size, then checks that plot.py finds the
lagrange sibling of each remap run, draws the overlays and field maps (PNG
files, listed on stdout), writes comparison.md, degrades to a note when the
compared run is missing, and that the alpha = 1/2 contour it draws lies on
the bar's outline.
"""

import contextlib
import importlib.util
import io
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from types import SimpleNamespace

import numpy as np

EXE, PLOT = sys.argv[1], sys.argv[2]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
HAVE_H5PY = importlib.util.find_spec("h5py") is not None


def lagremap(*args: str) -> None:
    env = dict(os.environ, OMP_PROC_BIND="false", OMP_NUM_THREADS="2")
    result = subprocess.run([EXE, "--quiet", *args], env=env, capture_output=True, text=True)
    # 1: a check fails (the short taylor cannot reach its final length).
    assert result.returncode in (0, 1), f"lagremap {' '.join(args)}: {result.stderr}"


def load_plot_module():
    spec = importlib.util.spec_from_file_location("plot", PLOT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


PLOT_MODULE = load_plot_module()


def plot(*args: str, command_line: bool = False) -> SimpleNamespace:
    """plot.py ARGS: as a process (as users run it), or in this interpreter
    (matplotlib is imported once: the test stays quick)."""
    if command_line:
        result = subprocess.run(["/usr/bin/python3", PLOT, *args], capture_output=True, text=True)
        return SimpleNamespace(returncode=result.returncode, stdout=result.stdout,
                               stderr=result.stderr)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = PLOT_MODULE.main(list(args))
    return SimpleNamespace(returncode=status, stdout=out.getvalue(), stderr=err.getvalue())


def is_png(path: str) -> bool:
    with open(path, "rb") as f:
        return f.read(8) == PNG_MAGIC and os.path.getsize(path) > 10000


class PlotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.root = tempfile.mkdtemp(prefix="lagremap_plot_")
        for mode in ("lagrange", "remap"):
            lagremap("--problem", "wilkins", "--mode", mode, "--scale", "0.5",
                     "--output", os.path.join(cls.root, f"wilkins_{mode}"))
        # 0.25 m cells in both modes: 22 x 8 on the 5.5 x 2 box, 20 x 4 on the bar.
        lagremap("--problem", "taylor", "--mode", "remap", "--set", "mesh.nx=22",
                 "--set", "mesh.ny=8", "--t-end", "4e-4",
                 "--output", os.path.join(cls.root, "taylor"))
        lagremap("--problem", "taylor", "--set", "mesh.nx=20", "--set", "mesh.ny=4",
                 "--t-end", "4e-4", "--output", os.path.join(cls.root, "taylor_lagrange"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.root, ignore_errors=True)

    def check_pngs(self, result, directory, expected):
        self.assertEqual(result.returncode, 0, result.stderr)
        listed = result.stdout.split()
        for name in expected:
            path = os.path.join(directory, name)
            self.assertIn(path, listed)
            self.assertTrue(is_png(path), path)

    def test_wilkins_overlay_finds_the_lagrange_sibling(self):
        remap = os.path.join(self.root, "wilkins_remap")
        result = plot(remap, command_line=True)
        self.check_pngs(result, remap, ["wilkins_profiles.png", "history.png"])
        with open(os.path.join(remap, "comparison.md")) as f:
            table = f.read()
        self.assertIn("| plastic_velocity |", table)
        self.assertIn("| 400 |", table)  # the lagrange reference of the remap check

    def test_taylor_outline_and_field_maps(self):
        remap = os.path.join(self.root, "taylor")
        result = plot(remap)
        expected = ["taylor.png", "history.png"]
        if HAVE_H5PY:
            expected += ["taylor_outline.png", "fields_map.png"]
        self.check_pngs(result, remap, expected)
        with open(os.path.join(remap, "comparison.md")) as f:
            self.assertIn("| final_length |", f.read())

    def test_missing_compare_run_is_a_note_not_an_error(self):
        remap = os.path.join(self.root, "wilkins_remap")
        out = os.path.join(self.root, "alone")
        result = plot(remap, "--compare", os.path.join(self.root, "nowhere"), "--out", out)
        self.check_pngs(result, out, ["wilkins_profiles.png"])
        self.assertIn("plot.py: note: --compare", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(out, "comparison.md")))

    @unittest.skipUnless(HAVE_H5PY, "python3-h5py is not installed")
    def test_alpha_contour_lies_on_the_initial_bar_outline(self):
        module = PLOT_MODULE
        run = module.read_run(os.path.join(self.root, "taylor"))
        initial = run.snapshots()[0]
        self.assertIsNotNone(initial.grid())  # the remap box is read as a grid
        fig, ax = module.plt.subplots()
        module.draw_alpha_contour(ax, initial, 0, colors="k")
        points = np.concatenate([p.vertices for c in ax.collections for p in c.get_paths()])
        module.plt.close(fig)
        # The bar [0, 5] x [-0.5, 0.5] is cell-aligned: alpha is 1 inside and 0
        # outside, so the contour runs half-way between cell centres, on the
        # bar's outline (off the wall x = 0, where the contour meets the box).
        x, y = points[:, 0], points[:, 1]
        distance = np.minimum(np.abs(np.abs(y) - 0.5) + np.maximum(x - 5.0, 0.0),
                              np.abs(x - 5.0) + np.maximum(np.abs(y) - 0.5, 0.0))
        self.assertLess(distance.max(), 1e-12)
        self.assertAlmostEqual(x.min(), 0.0, places=12)
        self.assertAlmostEqual(x.max(), 5.0, places=12)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
