#!/usr/bin/python3
"""perf/gpu_resources.py on a saved ptxas report (tests/data/ptxas_report.txt:
three entries of nvcc 13.0's -Xptxas=-v output for sm_90 of remap_step.cpp:
a Kokkos view copy, remapGradients' lambda, a stepLimitOverCellGeometries
instance that spills): our two kernels with their registers, stack and spill
bytes, the heaviest first; Kokkos' own copy left out; and its --bounds check
(a kernel past the general bound or its own line fails, a named kernel that
meets the general bound is told so, a malformed file is refused); a
`static` launcher's lambda and a functor template wrapping a launcher's
lambda named after the launcher.

  test_gpu_resources.py GPU_RESOURCES_PY REPORT
"""
import os
import subprocess
import sys
import tempfile


def main():
    script, report = sys.argv[1], sys.argv[2]
    out = subprocess.run(["/usr/bin/python3", script, report], capture_output=True, text=True,
                         check=True).stdout
    print(out, end="")
    rows = {line.split()[0]: line.split() for line in out.splitlines()[1:-1]}
    expected = {
        "stepLimitOverCellGeometries": ["1", "255", "752", "1036", "/", "992"],
        "remapGradients": ["1", "160", "0", "0", "/", "0"],
    }
    failures = [f"{name}: {rows.get(name)} != {want}" for name, want in expected.items()
                if rows.get(name, [None])[1:] != want]
    if list(rows) != list(expected):
        failures.append(f"kernels {list(rows)}, expected {list(expected)} (heaviest first, no Kokkos copy)")
    if not out.splitlines()[-1].startswith("2 lagremap kernels (2 instances), 1 spill"):
        failures.append("summary line: " + out.splitlines()[-1])
    failures += bounds_failures(script, report)
    failures += internal_linkage_failures(script, os.path.join(os.path.dirname(report),
                                                               "ptxas_report_internal.txt"))
    failures += wrapped_lambda_failures(script, os.path.join(os.path.dirname(report),
                                                             "ptxas_report_wrapped.txt"))
    if failures:
        sys.exit("test_gpu_resources: " + "; ".join(failures))
    print("test_gpu_resources: pass")


def wrapped_lambda_failures(script, report):
    """A functor template wrapping a launcher's lambda (SumsInArray<11, the
    lambda of remapAuditAndMoveNodes>: tests/data/ptxas_report_wrapped.txt)
    is named after the launcher, as the lambda alone would be."""
    out = subprocess.run(["/usr/bin/python3", script, report], capture_output=True, text=True,
                         check=True).stdout
    rows = out.splitlines()
    if len(rows) != 3 or rows[1].split()[:3] != ["remapAuditAndMoveNodes", "1", "72"]:
        return ["wrapped lambda not named after its launcher: " + out]
    return []


def internal_linkage_failures(script, report):
    """A `static` launcher's lambda (nvcc names it _INTERNAL_<hash>_<file>::
    lagremap::...: tests/data/ptxas_report_internal.txt, remapDensities of
    remap_step.cpp) is ours; a `required` kernel missing from the report fails
    the --bounds check (when the names stopped parsing, the check passed with
    none of the step's kernels in it)."""
    failures = []
    out = subprocess.run(["/usr/bin/python3", script, report], capture_output=True, text=True,
                         check=True).stdout
    if "remapDensities" not in out or "1 lagremap kernels" not in out:
        failures.append("internal-linkage kernel not labelled: " + out)
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "bounds.txt")
        for required, code in (("remapDensities", 0), ("remapDensities nodalSolve", 1)):
            with open(path, "w", encoding="utf-8") as bounds:
                bounds.write(f"* 128 256 0\nrequired {required}\n")
            result = subprocess.run(["/usr/bin/python3", script, "--bounds", path, report],
                                    capture_output=True, text=True)
            if result.returncode != code or (code and "nodalSolve: not in the report"
                                             not in result.stdout):
                failures.append(f"required {required}: exit {result.returncode}, " +
                                result.stdout + result.stderr)
    return failures


def bounds_failures(script, report):
    """--bounds: over the general bound fails and names the kernel; a kernel's
    own line lets it pass at its numbers; a named kernel with a looser line
    that meets the general bound is told to leave the file; a tighter line
    holds a kernel's occupancy."""
    failures = []
    with tempfile.TemporaryDirectory() as work:
        def run(text):
            path = os.path.join(work, "bounds.txt")
            with open(path, "w", encoding="utf-8") as bounds:
                bounds.write(text)
            return subprocess.run(["/usr/bin/python3", script, "--bounds", path, report],
                                  capture_output=True, text=True)
        general = run("# comment\n*  128 256 0\n")
        if general.returncode != 1 or "stepLimitOverCellGeometries: registers 255 > 128, stack " \
                "752 > 256, spill 2028 > 0" not in general.stdout or "remapGradients: " \
                "registers 160 > 128" not in general.stdout:
            failures.append("general bound not enforced: " + general.stdout + general.stderr)
        own = run("* 128 256 0\nstepLimitOverCellGeometries 255 752 2028\nremapGradients 160 0 0\n"
                  "computeCornerTerms 255 1032 3960\n")
        if own.returncode != 0 or "every kernel within its bound" not in own.stdout:
            failures.append("own bounds not honoured: " + own.stdout + own.stderr)
        tighter = run("* 128 256 0\nstepLimitOverCellGeometries 255 752 2000\nremapGradients 160 0 0\n")
        if tighter.returncode != 1 or "spill 2028 > 2000" not in tighter.stdout:
            failures.append("a kernel past its own line passed: " + tighter.stdout)
        met = run("* 256 1024 4096\nremapGradients 300 0 0\n")
        if "remapGradients now meets the general bound" not in met.stdout:
            failures.append("a kernel within the general bound not reported: " + met.stdout)
        held = run("* 256 1024 4096\nremapGradients 160 0 0\n")  # tighter: an occupancy
        if held.returncode != 0 or "now meets" in held.stdout:
            failures.append("a kernel held at its occupancy told to leave: " + held.stdout)
        lost = run("* 256 1024 4096\nremapGradients 128 0 0\n")
        if lost.returncode != 1 or "remapGradients: registers 160 > 128" not in lost.stdout:
            failures.append("a kernel past the occupancy its line holds passed: " + lost.stdout)
        bad = run("remapGradients 160 0\n")
        if bad.returncode == 0 or "expected 'KERNEL REGISTERS STACK SPILL'" not in bad.stderr:
            failures.append("a malformed bounds file accepted: " + bad.stderr)
    return failures


if __name__ == "__main__":
    main()
