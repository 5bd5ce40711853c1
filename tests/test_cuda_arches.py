#!/usr/bin/python3
"""scripts/cuda_arches.py against binaries whose GPU code is known: nvcc
compiles one kernel for sm_75 cubin + compute_86 PTX and for sm_90 cubin, and
the reader must list exactly those, and --require must pass and fail as it
should.   usage: test_cuda_arches.py NVCC cuda_arches.py"""
import os
import subprocess
import sys
import tempfile

nvcc, reader = sys.argv[1], sys.argv[2]
kernel = "__global__ void scale(double* x) { x[threadIdx.x] *= 2.0; }\nint main() { scale<<<1, 32>>>(nullptr); }\n"
with tempfile.TemporaryDirectory() as tmp:
    source = os.path.join(tmp, "kernel.cu")
    with open(source, "w") as f:
        f.write(kernel)
    cases = {
        "mixed": (["-gencode", "arch=compute_75,code=sm_75", "-gencode", "arch=compute_86,code=compute_86"],
                  {"elf sm_75", "ptx compute_86"}),
        "hopper": (["-arch=sm_90"], {"elf sm_90", "ptx compute_90"}),
    }
    failures = 0
    for name, (flags, expected) in cases.items():
        exe = os.path.join(tmp, name)
        subprocess.run([nvcc, *flags, source, "-o", exe], check=True)
        out = subprocess.run([sys.executable, reader, exe], check=True, capture_output=True, text=True).stdout
        listed = {line.split(":")[0] for line in out.splitlines()}
        if listed != expected:
            print(f"{name}: listed {sorted(listed)}, expected {sorted(expected)}")
            failures += 1
        for arch in ("sm_75", "sm_90"):
            wanted = f"elf {arch}" in expected
            rc = subprocess.run([sys.executable, reader, exe, "--require", arch], capture_output=True).returncode
            if (rc == 0) != wanted:
                print(f"{name}: --require {arch} returned {rc}")
                failures += 1
    sys.exit(1 if failures else 0)
