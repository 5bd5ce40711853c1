#!/usr/bin/python3
"""Per-kernel GPU resources from ptxas's verbose report (nvcc -Xptxas=-v).

Reads the compiler output on stdin (or from the files named) and prints, for
each lagremap kernel (the function whose lambda or functor Kokkos launches),
its registers per thread, stack frame and spill stores / loads in bytes: the
largest over its compiled instances (template instances, staged kernels of
one function, several translation units), the spills of the one that spills
most. Kokkos' own kernels (view copies,
fills) are left out.

  perf/gpu_resources.sh [ARCH]   compiles the kernels' translation units and
                                 pipes the report here (docs/performance.md)

  gpu_resources.py [--bounds FILE] [REPORT...]
    --bounds FILE: also check every kernel against FILE (perf/gpu_resource_bounds.txt:
    lines "KERNEL REGISTERS STACK SPILL", `*` the bound of every kernel not named;
    SPILL the spill stores plus loads, in bytes, of any instance; a kernel's own
    line is looser than `*` where it has not been brought within it yet, tighter
    everywhere where it holds an occupancy) and exit 1 where one is passed
"""
import re
import subprocess
import sys

ENTRY = re.compile(r"Compiling entry function '([^']+)' for '(sm_\d+)'")
FRAME = re.compile(r"(\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads")
USED = re.compile(r"Used (\d+) registers")
# what a launch runs: the first template argument of Kokkos' ParallelFor /
# Reduce / Scan (through the reduction's functor adapter)
LAUNCHED = re.compile(r"Parallel(?:For|Reduce|Scan)<(?:Kokkos::Impl::CudaFunctorAdapter<)?")
# ours: a lambda of a lagremap function, or a lagremap functor
LAMBDA_OF = re.compile(r"lagremap::(?:\w+::)*(\w+)\(")
FUNCTOR = re.compile(r"lagremap::(?:\w+::)*(\w+)")
# nvcc's prefix of a name of internal linkage (a `static` launcher's lambda):
# _INTERNAL_<hash>_<length>_<file>_<hash>::lagremap::...
INTERNAL = re.compile(r"_INTERNAL_[0-9A-Za-z_]+::|\(anonymous namespace\)::")


def demangle(names):
    out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True,
                         check=True).stdout
    return out.splitlines()


def kernel_label(demangled):
    launched = LAUNCHED.search(demangled)
    if not launched:
        return None
    functor = INTERNAL.sub("", demangled[launched.end():])
    if not functor.startswith("lagremap::"):
        return None  # Kokkos' own (a view copy or fill), whatever its value type
    lambda_of = LAMBDA_OF.match(functor)  # a name followed by "(": a function's lambda
    named = lambda_of or FUNCTOR.match(functor)
    if named and not lambda_of and wraps_a_lambda(functor, named.end()):
        named = LAMBDA_OF.search(functor, named.end())  # SumsInArray<N, a launcher's lambda>
    return named.group(1) if named else functor.split("<", 1)[0]


def wraps_a_lambda(functor, end):
    """Whether the functor named up to `end` is a class template whose
    arguments hold a lagremap function's lambda (not a function template's
    lambda, whose arguments are followed by its parameters)."""
    if not functor.startswith("<", end):
        return False
    depth = 0
    for i in range(end, len(functor)):
        depth += {"<": 1, ">": -1}.get(functor[i], 0)
        if depth == 0:
            return not functor.startswith("(", i + 1) and bool(
                LAMBDA_OF.search(functor[end:i]))
    return False


def parse(lines):
    """(mangled entry, arch, registers, stack, spill stores, spill loads) per kernel."""
    kernels, current = [], None
    for line in lines:
        entry = ENTRY.search(line)
        if entry:
            current = {"name": entry.group(1), "arch": entry.group(2), "stack": 0,
                       "spill_st": 0, "spill_ld": 0, "registers": 0}
            kernels.append(current)
            continue
        if current is None:
            continue
        frame = FRAME.search(line)
        if frame:
            current["stack"], current["spill_st"], current["spill_ld"] = map(int, frame.groups())
        used = USED.search(line)
        if used:
            current["registers"] = int(used.group(1))
            current = None  # "Used" closes an entry's report
    return kernels


def read_bounds(path):
    """{kernel or '*': (registers, stack, spill)} from a bounds file, and the
    kernels its `required` lines name (which the report must hold: a kernel
    whose name no longer parses would otherwise pass unseen)."""
    bounds, required = {}, []
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        fields = line.split("#", 1)[0].split()
        if not fields:
            continue
        if fields[0] == "required":
            required += fields[1:]
            continue
        if len(fields) != 4 or not all(f.isdigit() for f in fields[1:]):
            sys.exit(f"gpu_resources: {path}:{number}: expected 'KERNEL REGISTERS STACK SPILL'")
        bounds[fields[0]] = tuple(int(f) for f in fields[1:])
    if "*" not in bounds:
        sys.exit(f"gpu_resources: {path}: no '*' line (the bound of every kernel)")
    return bounds, required


def check(rows, bounds):
    """Lines saying which kernels pass their bounds (worst instance of each
    measure), and which named ones with a looser line now meet the general
    bound (a line tighter everywhere holds a kernel's occupancy: it stays)."""
    failures, met = [], []
    general = bounds["*"]
    for label, instances in rows:
        worst = (max(k["registers"] for k in instances), max(k["stack"] for k in instances),
                 max(k["spill_st"] + k["spill_ld"] for k in instances))
        bound = bounds.get(label, bounds["*"])
        over = [f"{name} {value} > {limit}" for name, value, limit
                in zip(("registers", "stack", "spill"), worst, bound) if value > limit]
        if over:
            failures.append(f"{label}: " + ", ".join(over))
        elif label in bounds and any(b > g for b, g in zip(bound, general)) and all(
                v <= g for v, g in zip(worst, general)):
            met.append(label)
    return failures, met


def main():
    args = sys.argv[1:]
    bounds, required = None, []
    if args[:1] == ["--bounds"]:
        if len(args) < 2:
            sys.exit("gpu_resources: --bounds needs a file")
        bounds, required = read_bounds(args[1])
        args = args[2:]
    lines = []
    for path in args or ["-"]:
        lines += (sys.stdin if path == "-" else open(path, encoding="utf-8")).read().splitlines()
    kernels = parse(lines)
    if not kernels:
        sys.exit("gpu_resources: no 'Compiling entry function' in the input (was -Xptxas=-v given?)")
    for kernel, name in zip(kernels, demangle([k["name"] for k in kernels])):
        kernel["label"] = kernel_label(name)
    ours = [k for k in kernels if k["label"]]
    by_label = {}
    for k in ours:
        by_label.setdefault(k["label"], []).append(k)
    rows = []
    for label, instances in by_label.items():
        instances.sort(key=lambda k: (k["spill_st"] + k["spill_ld"], k["stack"], k["registers"]),
                       reverse=True)
        rows.append((label, instances))
    rows.sort(key=lambda row: (row[1][0]["spill_st"] + row[1][0]["spill_ld"], row[1][0]["registers"],
                               row[1][0]["stack"]), reverse=True)
    print(f"{'kernel':<34} {'inst':>4} {'registers':>9} {'stack [B]':>9} {'spill st/ld [B]':>16}"
          f"  ({kernels[0]['arch']})")
    for label, instances in rows:
        # the largest of each measure over the kernel's instances
        registers = max(k["registers"] for k in instances)
        stack = max(k["stack"] for k in instances)
        k = instances[0]  # the one that spills most
        print(f"{label:<34} {len(instances):>4} {registers:>9} {stack:>9} "
              f"{str(k['spill_st']) + ' / ' + str(k['spill_ld']):>16}")
    spilling = sum(1 for _, inst in rows if inst[0]["spill_st"] + inst[0]["spill_ld"] > 0)
    print(f"{len(rows)} lagremap kernels ({len(ours)} instances), {spilling} spill")
    if bounds is None:
        return
    failures, met = check(rows, bounds)
    reported = {label for label, _ in rows}
    failures += [f"{label}: not in the report (its launch's name no longer parses, or it is gone)"
                 for label in required if label not in reported]
    general = bounds["*"]
    for label in met:
        print(f"gpu_resources: {label} now meets the general bound: remove its line from the "
              "bounds file")
    if failures:
        for failure in failures:
            print(f"gpu_resources: over its bound or missing: {failure}")
        sys.exit(f"gpu_resources: {len(failures)} kernels over their bounds or missing")
    print(f"gpu_resources: every kernel within its bound ({general[0]} registers, {general[1]} B "
          f"stack, {general[2]} B spills; {len(bounds) - 1} kernels with bounds of their own)")


if __name__ == "__main__":
    main()
