#!/usr/bin/python3
"""scripts/convergence.py (ctest, label quick).

Usage: test_convergence.py CONVERGENCE_PY [LAGREMAP_EXE]

Without LAGREMAP_EXE (no build needed, no lagremap run): the arithmetic on synthetic data of
known order -- the observed order between two runs, the three-run order for
constant and non-constant refinement ratios (Celik et al.'s equation),
Richardson's extrapolated value, Roache's GCI, and the oscillatory,
vanishing and diverging cases -- and the tables and --require-order on
hand-written summary.json files.  With LAGREMAP_EXE, only what needs it:
the command line's one-line errors (unknown problem, lagremap refusing its
arguments or missing), a study of two tiny sod runs, read again instead of
rerun, and --sweep on them.
"""

import contextlib
import importlib.util
import io
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SCRIPT = sys.argv[1]
EXE = sys.argv[2] if len(sys.argv) > 2 else None


def load_module():
    spec = importlib.util.spec_from_file_location("convergence", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


cv = load_module()


def run_main(*args):
    """convergence.py ARGS in this interpreter: (status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = cv.main(list(args))
    return status, out.getvalue(), err.getvalue()


def write_run(directory, cells, checks=None, l1=None, steps=10, mesh=None):
    """A summary.json; with mesh (nx, ny, nz) its configuration holds the
    mesh keys, from which the script counts the refined directions (without,
    from how the cell count grows with the scale)."""
    os.makedirs(directory, exist_ok=True)
    summary = {"problem": "synthetic", "mode": "lagrange", "cells": cells, "steps": steps,
               "status": "completed", "wall_seconds": 0.5, "checks": checks or {}}
    if mesh is not None:
        summary["config"] = {f"mesh.n{axis}": str(n) for axis, n in zip("xyz", mesh)}
    if l1 is not None:
        summary["l1_errors"] = dict(l1, note="synthetic")
    with open(os.path.join(directory, "summary.json"), "w") as f:
        json.dump(summary, f)


class Arithmetic(unittest.TestCase):
    def test_pair_order_of_a_power_law(self):
        for p in (0.5, 1.0, 2.0):
            e = [0.3 * h ** p for h in (0.1, 0.05)]
            self.assertAlmostEqual(cv.pair_order(e[0], e[1], 0.1, 0.05), p, places=12)
        self.assertIsNone(cv.pair_order(0.0, 1e-3, 0.1, 0.05))
        self.assertIsNone(cv.pair_order(None, 1e-3, 0.1, 0.05))

    def test_constant_ratio_second_order(self):
        # f = 1 + 0.3 h^2 at h = 0.25, 0.5, 1 (finest first): p = 2, f_ext = 1.
        h = [0.25, 0.5, 1.0]
        f = [1 + 0.3 * x ** 2 for x in h]
        result = cv.three_grid(f, h)
        self.assertEqual(result.status, "ok")
        self.assertAlmostEqual(result.order, 2.0, places=12)
        self.assertAlmostEqual(result.extrapolated, 1.0, places=12)
        # GCI_fine = 1.25 |f2 - f1| / |f1| / (r^p - 1)
        gci = 1.25 * abs(f[1] - f[0]) / f[0] / (2 ** 2 - 1)
        self.assertAlmostEqual(result.gci_fine, gci, places=14)
        # the fine-grid error |f1 - f_ext| / f1 lies below the GCI (= 1.25 of it here)
        self.assertAlmostEqual(result.gci_fine, 1.25 * abs(f[0] - 1.0) / f[0], places=14)

    def test_decreasing_values_first_order(self):
        h = [0.1, 0.2, 0.4]
        f = [5.0 - 2.0 * x for x in h]
        result = cv.three_grid(f, h)
        self.assertAlmostEqual(result.order, 1.0, places=12)
        self.assertAlmostEqual(result.extrapolated, 5.0, places=12)

    def test_non_constant_ratio_solves_celiks_equation(self):
        # ratios 1.5 and 2.5: the constant-ratio formula would be wrong.
        for p in (0.7, 1.0, 1.6, 2.0, 3.0):
            h = [1.0, 1.5, 3.75]
            f = [2.0 + 0.4 * x ** p for x in h]
            result = cv.three_grid(f, h)
            self.assertEqual(result.status, "ok", p)
            self.assertAlmostEqual(result.order, p, places=9)
            self.assertAlmostEqual(result.extrapolated, 2.0, places=9)
        # ratios 2 and 1.5: the fixed-point iteration settles
        h = [1.0, 2.0, 3.0]
        f = [2.0 + 0.4 * x ** 1.3 for x in h]
        self.assertAlmostEqual(cv.three_grid(f, h).order, 1.3, places=9)
        # a ratio pair whose fine ratio is the larger: 2 then 1.2
        h = [0.05, 0.1, 0.12]
        f = [1 - 3 * x ** 1.5 for x in h]
        result = cv.three_grid(f, h)
        self.assertAlmostEqual(result.order, 1.5, places=9)
        self.assertAlmostEqual(result.extrapolated, 1.0, places=9)

    def test_oscillatory_vanishing_and_diverging(self):
        h = [0.25, 0.5, 1.0]
        self.assertEqual(cv.three_grid([1.0, 1.1, 1.05], h).status, "oscillatory")
        self.assertEqual(cv.three_grid([1.0, 1.0, 1.2], h).status, "n/a")
        self.assertEqual(cv.three_grid([1.0, None, 1.2], h).status, "n/a")
        # changes growing under refinement: no positive order
        diverging = cv.three_grid([1.0 + 0.3, 1.0 + 0.1, 1.0], h)
        self.assertEqual(diverging.status, "diverging")
        self.assertIsNone(diverging.extrapolated)
        self.assertIsNone(diverging.gci_fine)
        self.assertEqual(diverging.order_text(), "diverging")


class Tables(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="lagremap_convergence_")

    def tearDown(self):
        shutil.rmtree(self.root)

    def test_error_table_orders_and_required_order(self):
        # 1D: cells 50, 100, 200; density second order, pressure first.
        for scale, cells in ((0.25, 50), (0.5, 100), (1, 200)):
            h = 1.0 / cells
            write_run(os.path.join(self.root, f"scale_{scale:g}"), cells, mesh=(cells, 1, 1),
                      l1={"density": 3 * h ** 2, "velocity": 2 * h, "pressure": None})
        status, out, err = run_main("synthetic", "--scales", "0.25,0.5,1", "--output", self.root,
                                    "--table-only", "--wall", "--require-order", "density=1.9")
        self.assertEqual(status, 0, err)
        self.assertIn("h = cells^(-1/1)", out)
        self.assertIn("| 2.000 |", out)  # the density's order
        self.assertIn("| 1.000 |", out)  # the velocity's
        self.assertIn("| 0.5 |", out)  # wall seconds
        self.assertTrue(os.path.exists(os.path.join(self.root, "convergence.md")))
        status, _, err = run_main("synthetic", "--scales", "0.25,0.5,1", "--output", self.root,
                                  "--table-only", "--require-order", "velocity=1.5")
        self.assertEqual(status, 1)
        self.assertEqual(len(err.strip().splitlines()[-1:]), 1)
        self.assertIn("velocity: observed order 1.000 between scales 0.25 and 0.5 is below 1.5",
                      err)
        status, _, err = run_main("synthetic", "--scales", "0.25,0.5,1", "--output", self.root,
                                  "--table-only", "--require-order", "pressure=0.5")
        self.assertEqual(status, 1)  # no pressure errors: no order, which is below any bound
        status, _, err = run_main("synthetic", "--scales", "0.25,0.5,1", "--output", self.root,
                                  "--table-only", "--require-order", "entropy=1")
        self.assertEqual(status, 2)
        self.assertIn("no quantity 'entropy'", err)

    def test_check_table_richardson_and_gci(self):
        # 2D: cells 10x10, 20x20, 40x40; a check converging at order 2 to 4.6,
        # one oscillating, one failing at the coarsest scale.
        for scale, n in ((0.5, 10), (1, 20), (2, 40)):
            h = 1.0 / n
            checks = {
                "length": {"value": 4.6 + 50 * h ** 2, "reference": 4.62, "tolerance": 0.05,
                           "applies": True, "pass": n > 10},
                "wiggle": {"value": {10: 1.0, 20: 1.2, 40: 1.1}[n], "reference": 1.0,
                           "tolerance": 1.0, "applies": False, "pass": True},
            }
            write_run(os.path.join(self.root, f"scale_{scale:g}"), n * n, checks=checks)
        status, out, err = run_main("synthetic", "--output", self.root, "--table-only",
                                    "--require-order", "length=1.9")
        self.assertEqual(status, 0, err)
        self.assertIn("h = cells^(-1/2)", out)
        self.assertIn("FAIL: length", out)  # the coarsest run's checks
        row = next(line for line in out.splitlines() if line.startswith("| length |"))
        cells = [c.strip() for c in row.strip("|").split("|")]
        self.assertEqual(cells[-3], "2")  # order
        self.assertEqual(cells[-2], "4.6")  # f_ext
        f1, f2 = 4.6 + 50 / 1600, 4.6 + 50 / 400
        self.assertEqual(cells[-1], format(100 * 1.25 * (f2 - f1) / f1 / 3, ".3g") + "%")
        self.assertIn("| wiggle | 1 (n/a) |", out)
        self.assertIn("oscillatory", out)
        status, _, err = run_main("synthetic", "--output", self.root, "--table-only",
                                  "--require-order", "wiggle=0.5")
        self.assertEqual(status, 1)
        self.assertIn("wiggle: observed order n/a from scales 0.5, 1, 2 is below 0.5", err)

    def test_sweep_and_a_restarted_runs_wall_time(self):
        # summary.json of a run continued with --restart times its last piece:
        # 100 cells x 300 steps in 2 s of 400 steps in all.
        restarted = os.path.join(self.root, "restarted")
        write_run(restarted, 100, mesh=(100, 1, 1), steps=400, checks={
            "length": {"value": 4.6, "reference": 4.62, "tolerance": 0.05, "applies": True,
                       "pass": True},
            "speed": {"value": 3.0, "reference": 0.0, "tolerance": 1.0, "applies": True,
                      "pass": False},
            "radius": {"value": 1.0, "reference": 2.0, "tolerance": 0.1, "applies": False,
                       "pass": False}})
        with open(os.path.join(restarted, "summary.json")) as f:
            summary = json.load(f)
        summary.update(wall_seconds=2.0, cell_steps_per_second={"total": 100 * 300 / 2.0})
        with open(os.path.join(restarted, "summary.json"), "w") as f:
            json.dump(summary, f)
        status, out, err = run_main("--sweep", restarted, "--wall")
        self.assertEqual(status, 0, err)
        self.assertIn("| synthetic | lagrange | 100 x 1 x 1 | 100 | 400 | 2 (last piece: 300 of "
                      "400 steps) | checks fail | length | 4.6 | 4.62 | 0.05 | pass |", out)
        self.assertIn("| speed | 3 | 0 | 1 | FAIL |", out)
        self.assertIn("| radius | 1 | 2 | 0.1 | n/a |", out)
        status, _, err = run_main("--sweep", os.path.join(self.root, "nothing"))
        self.assertEqual(status, 2)
        self.assertIn("holds no summary.json", err)

    def test_bad_scales_and_missing_runs(self):
        for scales in ("1", "0,1", "a,b", "1,1,2", "-1,2"):
            status, _, err = run_main("sod", "--scales", scales, "--table-only",
                                      "--output", self.root)
            self.assertEqual(status, 2, scales)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertIn("--scales", err)
        status, _, err = run_main("sod", "--scales", "1,2", "--table-only", "--output", self.root)
        self.assertEqual(status, 2)
        self.assertIn("no run at scale 1", err)


@unittest.skipIf(EXE is None, "needs a lagremap binary")
class CommandLine(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.root = tempfile.mkdtemp(prefix="lagremap_convergence_cli_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.root)

    def command(self, *args):
        result = subprocess.run(["/usr/bin/python3", SCRIPT, *args], capture_output=True,
                                text=True)
        return result.returncode, result.stdout, result.stderr

    def test_unknown_problem_and_refused_arguments(self):
        status, _, err = self.command("nosuch", "--lagremap", EXE, "--output", self.root)
        self.assertEqual(status, 2)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn("unknown problem 'nosuch'", err)
        self.assertIn("sod", err)
        status, _, err = self.command("sod", "--scales", "0.05,0.1", "--lagremap", EXE,
                                      "--output", os.path.join(self.root, "refused"),
                                      "--", "--set", "nosuch.key=1")
        self.assertEqual(status, 2)
        self.assertIn("lagremap refused sod --scale 0.05", err.strip().splitlines()[-1])
        self.assertIn("nosuch.key", err.strip().splitlines()[-1])
        status, _, err = self.command("sod", "--lagremap", os.path.join(self.root, "missing"),
                                      "--output", self.root)
        self.assertEqual(status, 3)
        self.assertIn("cannot start lagremap", err)

    def test_runs_reuse_and_sweep(self):
        root = os.path.join(self.root, "sod")
        args = ["sod", "--scales", "0.05,0.1", "--lagremap", EXE, "--output", root]
        status, out, err = self.command(*args)
        self.assertEqual(status, 0, err)
        self.assertIn("L1 density", out)
        if importlib.util.find_spec("matplotlib") is not None:
            with open(os.path.join(root, "convergence.png"), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        status, out2, err = self.command(*args)
        self.assertEqual(status, 0, err)
        self.assertIn("reusing", err)
        self.assertEqual(out, out2)
        status, out, err = self.command("--sweep", os.path.join(root, "scale_0.05"),
                                        os.path.join(root, "scale_0.1"), "--wall")
        self.assertEqual(status, 0, err)
        self.assertIn("| sod | lagrange | 10 x 1 x 1 | 10 |", out)
        self.assertIn("| sod | lagrange | 20 x 1 x 1 | 20 |", out)
        self.assertIn("l1_density", out)


if __name__ == "__main__":
    loader = unittest.TestLoader()
    classes = [CommandLine] if EXE else [Arithmetic, Tables, CommandLine]
    suite = unittest.TestSuite(loader.loadTestsFromTestCase(c) for c in classes)
    result = unittest.TextTestRunner(verbosity=2).run(suite)
    sys.exit(0 if result.wasSuccessful() else 1)
