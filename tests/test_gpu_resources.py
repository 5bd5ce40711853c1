#!/usr/bin/python3
"""perf/gpu_resources.py on a saved ptxas report (tests/data/ptxas_report.txt:
three entries of nvcc 13.0's -Xptxas=-v output for sm_90 of remap_step.cpp:
a Kokkos view copy, remapGradients' lambda, a stepLimitOverCellGeometries
instance that spills): our two kernels with their registers, stack and spill
bytes, the heaviest first; Kokkos' own copy left out.

  test_gpu_resources.py GPU_RESOURCES_PY REPORT
"""
import subprocess
import sys


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
    if failures:
        sys.exit("test_gpu_resources: " + "; ".join(failures))
    print("test_gpu_resources: pass")


if __name__ == "__main__":
    main()
