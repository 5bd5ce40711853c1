#!/usr/bin/env bash
# Memory per cell of a problem: two runs, at --scale 1 and --scale 2, and the
# difference of their peak resident sets (summary.json memory.peak_bytes) over
# the difference of their cell counts, so that the executable, the libraries
# and the thread stacks do not count. Also the inventory of the Views: each
# label's bytes per cell at the moment the Views' sum peaked (Kokkos' tools
# interface, perf/view_memory.cpp, built here). Prints a markdown table.
#
#   perf/memory.sh PROBLEM [lagremap arguments...]
#     e.g. perf/memory.sh taylor --mode remap --t-end 5e-7
#   Environment: LAGREMAP_EXE (default build/lagremap), MAX_BYTES_PER_CELL
#     (exit 1 when the resident set per cell is above it), OMP_NUM_THREADS (2).
# Builds nothing but the small tools library (g++).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[ $# -ge 1 ] || { echo "usage: perf/memory.sh PROBLEM [lagremap arguments...]" >&2; exit 2; }
problem=$1
shift
exe=${LAGREMAP_EXE:-$here/build/lagremap}
[ -x "$exe" ] || { echo "memory: no $exe (scripts/build.sh --target lagremap)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -std=c++17 -O2 -shared -fPIC "$here/perf/view_memory.cpp" -o "$work/libview_memory.so"

for scale in 1 2; do
  # Kokkos 3 reads KOKKOS_PROFILE_LIBRARY, Kokkos 4 KOKKOS_TOOLS_LIBS
  status=0
  KOKKOS_PROFILE_LIBRARY="$work/libview_memory.so" KOKKOS_TOOLS_LIBS="$work/libview_memory.so" \
    LAGREMAP_VIEW_MEMORY_OUT="$work/views.$scale" OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} \
    "$exe" --problem "$problem" "$@" --scale "$scale" --quiet --output "$work/out.$scale" \
    > "$work/log.$scale" 2>&1 || status=$?
  if [ ! -f "$work/out.$scale/summary.json" ] || [ ! -f "$work/views.$scale" ]; then
    tail -n 5 "$work/log.$scale" >&2
    echo "memory: the run at --scale $scale failed (exit $status)" >&2
    exit 1
  fi
done

/usr/bin/python3 - "$work" "$problem $*" "${MAX_BYTES_PER_CELL:-}" <<'PY'
import json, sys
work, run, limit = sys.argv[1], sys.argv[2], sys.argv[3]
summary = [json.load(open(f"{work}/out.{s}/summary.json")) for s in (1, 2)]
cells = [s["cells"] for s in summary]
rss = [s["memory"]["peak_bytes"]["max"] for s in summary]
views, peak = [], []
for s in (1, 2):
    rows = {}
    for line in open(f"{work}/views.{s}"):
        if line.startswith("# peak"):
            peak.append(int(line.split()[2]))
            continue
        size, space, label = line.split(maxsplit=2)
        rows[label.strip()] = int(size)
    views.append(rows)
extra = cells[1] - cells[0]
per_cell = (rss[1] - rss[0]) / extra
views_per_cell = (peak[1] - peak[0]) / extra
print(f"{run}: --scale 1 and 2, {cells[0]} and {cells[1]} cells")
print(f"peak resident set: {per_cell:,.0f} bytes per cell (Views at their peak: "
      f"{views_per_cell:,.0f})\n")
print("| View (label less lagremap::) | bytes per cell |\n|---|---:|")
labels = set(views[0]) | set(views[1])
table = sorted(((views[1].get(k, 0) - views[0].get(k, 0)) / extra, k) for k in labels)
for size, label in reversed(table):
    if size >= 0.5:
        print(f"| `{label.replace('lagremap::', '')}` | {size:,.0f} |")
if limit and per_cell > float(limit):
    sys.exit(f"memory: {per_cell:,.0f} bytes per cell, above the bound of {float(limit):,.0f}")
PY
