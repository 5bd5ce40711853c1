#!/usr/bin/env bash
# Instructions per cell-step of each kernel of a problem, counted by callgrind
# (repeatable on shared machines, where wall time is not): two runs of
# STEPS_SHORT and STEPS_LONG steps on one thread, their difference divided by
# cells x (STEPS_LONG - STEPS_SHORT), so that set-up and output do not count.
# Prints a markdown table, kernels by cost.
#
#   perf/instructions.sh PROBLEM [lagremap arguments...]
#     e.g. perf/instructions.sh taylor --mode remap --scale 0.5
#   Environment: LAGREMAP_EXE (default build/lagremap), STEPS_SHORT (10),
#     STEPS_LONG (30), INSTRUCTIONS_TOP (rows, default 14), FROM_STEP (0):
#     count from a checkpoint of step FROM_STEP instead of the initial state
#     (a plain run writes it first). The first steps of an impact leave most
#     of the domain at rest, where the remap has nothing to sweep; mid-run
#     counts are the representative ones.
# Builds nothing (scripts/build.sh --target lagremap first); needs valgrind.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[ $# -ge 1 ] || { echo "usage: perf/instructions.sh PROBLEM [lagremap arguments...]" >&2; exit 2; }
problem=$1
shift
exe=${LAGREMAP_EXE:-$here/build/lagremap}
short=${STEPS_SHORT:-10}
long=${STEPS_LONG:-30}
[ -x "$exe" ] || { echo "instructions: no $exe (scripts/build.sh --target lagremap)" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "instructions: valgrind is not installed" >&2; exit 1; }
[ "$long" -gt "$short" ] || { echo "instructions: STEPS_LONG must exceed STEPS_SHORT" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

from=${FROM_STEP:-0}
restart=()
if [ "$from" -gt 0 ]; then
  # The step limit ends a run with status 3 ("max_steps reached"), on purpose,
  # and leaves its last state in a checkpoint.
  OMP_PROC_BIND=false "$exe" --problem "$problem" "$@" --set "numerics.max_steps=$from" \
    --quiet --output "$work/out.start" > "$work/log.start" 2>&1 || true
  grep -q "max_steps reached" "$work/log.start" ||
    { tail -n 5 "$work/log.start" >&2; echo "instructions: the run ended before $from steps" >&2; exit 1; }
  restart=(--restart "$work/out.start/checkpoint.h5")
fi

profile() {  # profile STEPS: callgrind output of a run stopped after STEPS more steps
  local steps=$1
  shift
  OMP_NUM_THREADS=1 OMP_PROC_BIND=false valgrind --tool=callgrind \
    --callgrind-out-file="$work/cg.$steps" "$exe" --problem "$problem" "$@" \
    ${restart[@]+"${restart[@]}"} --set "numerics.max_steps=$((from + steps))" --quiet \
    --output "$work/out.$steps" > "$work/log.$steps" 2>&1 || true
  grep -q "max_steps reached" "$work/log.$steps" ||
    { tail -n 5 "$work/log.$steps" >&2; echo "instructions: the run ended before $steps steps" >&2; exit 1; }
  callgrind_annotate --threshold=100 "$work/cg.$steps" > "$work/annotate.$steps" 2>/dev/null
}
profile "$short" "$@"
profile "$long" "$@"
cells=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['cells'])" \
  "$work/out.$long/summary.json")

/usr/bin/python3 - "$work/annotate.$short" "$work/annotate.$long" "$cells" \
  "$((long - short))" "${INSTRUCTIONS_TOP:-14}" "$problem $*${FROM_STEP:+ (from step $from)}" <<'EOF'
import re, sys

short_file, long_file, cells, steps, top, title = sys.argv[1:7]
cell_steps = int(cells) * int(steps)

def kernel_name(symbol):
    """The kernel a symbol belongs to: the lagremap function whose lambda it is
    (Kokkos' dispatch of it included), else the function itself."""
    symbol = re.sub(r"\[.*\]$", "", symbol).strip()
    m = re.search(r"lagremap::(?:[A-Za-z_]+::)*([A-Za-z_]+)(?:<[^()]*>)?\(", symbol)
    if m:
        qualified = re.search(r"lagremap::((?:[A-Za-z_]+::)*[A-Za-z_]+)(?:<[^()]*>)?\(", symbol).group(1)
        return qualified
    return re.sub(r"\(.*", "", symbol.split(":", 1)[-1])[:60]

def costs(path):
    totals = {}
    for line in open(path):
        m = re.match(r"\s*([\d,]+)\s+\([\s\d.]+%\)\s+(.*)", line)
        if not m or "PROGRAM TOTALS" in line:
            continue
        name = kernel_name(m.group(2))
        totals[name] = totals.get(name, 0) + int(m.group(1).replace(",", ""))
    return totals

a, b = costs(short_file), costs(long_file)
diff = {k: b.get(k, 0) - a.get(k, 0) for k in set(a) | set(b)}
total = sum(v for v in diff.values())
rows = sorted(diff.items(), key=lambda kv: -kv[1])
print(f"Instructions per cell-step, {title} ({cells} cells, steps {int(steps)} apart, 1 thread)\n")
print("| function (self cost) | per cell-step | share |")
print("|---|---:|---:|")
shown = 0
for name, value in rows[: int(top)]:
    print(f"| `{name}` | {value / cell_steps:,.0f} | {100 * value / total:.1f}% |")
    shown += value
print(f"| everything else | {(total - shown) / cell_steps:,.0f} | {100 * (total - shown) / total:.1f}% |")
print(f"| **total** | **{total / cell_steps:,.0f}** | |")
EOF
