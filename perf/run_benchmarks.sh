#!/usr/bin/env bash
# Runs the Lagrangian-step benchmarks (perf/bench_lagrange.cpp) at 1 and 2
# Kokkos threads and prints kernel | cell-steps/s at 1 thread | at 2 | speed-up.
# Builds nothing: build first with `scripts/build.sh --target bench_lagrange`
# (and `--target bench_constitutive` for the solid kernels).
#
#   perf/run_benchmarks.sh [BUILD_DIR] [TABLE.md]
#     BUILD_DIR  default: ../build relative to this script
#     TABLE.md   optional: the table is also written there (markdown)
#   Environment: BENCH_EXE (default bench_lagrange; bench_constitutive runs the
#       constitutive kernels and solid full steps, "bench_lagrange
#       bench_constitutive" both, one table each),
#     LAGREMAP_BENCH_N (cells per edge, default 60),
#     LAGREMAP_BENCH_WARMUP (steps before timing, default 40),
#     LAGREMAP_BENCH_CELLS, LAGREMAP_BENCH_SOLID_SCALE (bench_constitutive's sizes),
#     BENCH_MIN_TIME (seconds per benchmark, default 0.2),
#     BENCH_REPETITIONS (default 3; the table shows the median),
#     BENCH_THREADS (default "1 2"), BENCH_FILTER (--benchmark_filter regex).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${1:-$here/../build}
table_md=${2:-}
exe_names=${BENCH_EXE:-bench_lagrange}
for name in $exe_names; do
  exe=$build/perf/$name
  [ -x "$exe" ] || { echo "run_benchmarks: no $exe (build the $name target first)" >&2; exit 1; }
done
min_time=${BENCH_MIN_TIME:-0.2}
repetitions=${BENCH_REPETITIONS:-3}
threads=${BENCH_THREADS:-1 2}
filter=${BENCH_FILTER:-.}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Busy CPU ticks of the whole machine so far (user nice system irq softirq steal).
busy_ticks() {
  local f
  f=($(head -1 /proc/stat))
  echo $((f[1] + f[2] + f[3] + f[6] + f[7] + f[8]))
}
hz=$(getconf CLK_TCK)

# Prints (and writes to TABLE.md, if given) the table of one executable's runs.
#   print_table TABLE_MODE BUSY_LOG JSON...  (TABLE_MODE: w creates TABLE.md, a appends)
print_table() {
  local mode=$1 busy=$2
  shift 2
  BUSY_LOG=$busy TABLE_MODE=$mode /usr/bin/python3 - "$table_md" "$@" <<'EOF'
import json, os, sys

table_md, paths = sys.argv[1], sys.argv[2:]
runs = [json.load(open(p)) for p in paths]
ctx = runs[0]["context"]
threads = [r["context"].get("kokkos_threads", "?") for r in runs]

def rates(run):
    # The median over repetitions when there are some, else the single run.
    out = {}
    for b in run["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b.get("run_name", b["name"]).replace("/manual_time", "")
        if b.get("error_occurred"):
            out[name] = None
            continue
        out[name] = b.get("cell_steps_per_second", b.get("cells_per_second"))
    return out

per_run = [rates(r) for r in runs]
names = list(per_run[0])
header = ["kernel"] + [f"{t} thr [Mcell/s]" for t in threads]
if len(runs) >= 2:
    header.append(f"speed-up {threads[0]}->{threads[-1]}")
rows = []
for name in names:
    vals = [pr.get(name) for pr in per_run]
    row = [name] + [f"{v / 1e6:.3f}" if v else "error" for v in vals]
    if len(runs) >= 2:
        row.append(f"{vals[-1] / vals[0]:.2f}x" if vals[0] and vals[-1] else "-")
    rows.append(row)

if "summary" in ctx:  # a driver that describes its own set-up (bench_constitutive)
    title = (f"{ctx['summary']}; rates are cells (x steps for full steps) per second, manual "
             f"time, median of {runs[0]['benchmarks'][0].get('repetitions', 1)} repetitions; "
             f"other processes' mean busy cores during each run:"
             f"{os.environ.get('BUSY_LOG', '')}")
else:
    title = (f"sedov {ctx.get('n', '?')}^3 = {ctx.get('cells', '?')} cells, "
             f"{ctx.get('execution_space', '?')}, warm-up {ctx.get('warmup_steps', '?')} steps "
             f"({ctx.get('shocked_cells', '?')} shocked cells); rates are cells (x steps for "
             f"BM_FullStep) per second, manual time, median of "
             f"{runs[0]['benchmarks'][0].get('repetitions', 1)} repetitions; other processes' "
             f"mean busy cores during each run:{os.environ.get('BUSY_LOG', '')}")
widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]
fmt = lambda r: "  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(r, widths)))
print(title)
print(fmt(header))
print("  ".join("-" * w for w in widths))
for r in rows:
    print(fmt(r))

if table_md:
    mode = os.environ.get("TABLE_MODE", "w")
    with open(table_md, mode) as f:
        f.write(f"{title}\n\n" if mode == "w" else f"\n{title}\n\n")
        f.write("| " + " | ".join(header) + " |\n")
        f.write("|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|\n")
        for r in rows:
            f.write("| " + " | ".join(r) + " |\n")
    print(f"(table written to {table_md})", file=sys.stderr)
EOF
}

table_mode=w
for name in $exe_names; do
  exe=$build/perf/$name
  jsons=()
  busy_log=""
  for t in $threads; do
    echo "== $name, $t thread(s) ==" >&2
    # Console report to stderr (progress); the JSON file feeds the table.
    # Pinned threads share their core with any other busy process, so the CPU
    # that other processes used meanwhile is measured and reported.
    ticks0=$(busy_ticks)
    start=$(date +%s.%N)
    OMP_PROC_BIND=spread OMP_PLACES=threads /usr/bin/time -f "%U %S" -o "$work/time$t" \
      "$exe" --kokkos-threads="$t" \
      --benchmark_min_time="$min_time" --benchmark_filter="$filter" \
      --benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true \
      --benchmark_out="$work/$name$t.json" --benchmark_out_format=json >&2
    ticks1=$(busy_ticks)
    end=$(date +%s.%N)
    other=$(awk -v d=$((ticks1 - ticks0)) -v hz="$hz" -v t0="$start" -v t1="$end" \
      '{ printf "%.2f", (d / hz - $1 - $2) / (t1 - t0) }' "$work/time$t")
    awk -v o="$other" 'BEGIN { exit !(o > 0.2) }' &&
      echo "run_benchmarks: warning: other processes kept $other cores busy during the $t-thread run" >&2
    jsons+=("$work/$name$t.json")
    busy_log="$busy_log ${t}thr:$other"
  done
  print_table "$table_mode" "$busy_log" "${jsons[@]}"
  table_mode=a  # one table per executable, all in the same TABLE.md
done
