#!/usr/bin/env bash
# Weak scaling (docs/method.md §7.5): the same number of cells per rank on 1, 2, 4 and
# 8 ranks (more or fewer with WEAK_RANKS), one thread each. The `sedov` blast
# on an (a n) x (b n) x (c n) mesh for a 1 x 1 x 1, 2 x 1 x 1, 2 x 2 x 1,
# 2 x 2 x 2 ... process grid (a x b x c = ranks; the octant is then cut into
# stretched cells, which changes the answer, not the work), a fixed number of
# steps. Prints, per rank count: time per step (time loop only), weak-scaling
# efficiency against 1 rank, the halo's share of the step, the set-up time
# and its phases, the largest rank's peak memory and the halo's bytes and
# messages per step (summary.json of each run).
#
#   perf/weak_scaling.sh [OUT_DIR]
#     OUT_DIR  default: out/weak_scaling (table.md, results.csv, run_*/)
#   Environment: WEAK_CELLS_PER_EDGE n (default 24: 13,824 cells per rank),
#     WEAK_RANKS (default "1 2 4 8"), WEAK_STEPS (default 20),
#     LAGREMAP_BUILD_DIR (default build/).
# On a machine with fewer cores than ranks the ranks share cores
# (oversubscribed): the table says how many ranks each core carried, and
# the time per step then measures the machine, not the code; the halo bytes,
# messages, set-up phases and memory per rank do not depend on it.
# docs/performance.md (Parallel runs) models larger machines from these.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}
out=${1:-$here/out/weak_scaling}
edge=${WEAK_CELLS_PER_EDGE:-24}
rank_counts=${WEAK_RANKS:-1 2 4 8}
steps=${WEAK_STEPS:-20}
exe=$build/lagremap
[ -x "$exe" ] || { echo "weak_scaling: no $exe (run scripts/build.sh first)" >&2; exit 1; }
[[ "$edge" =~ ^[1-9][0-9]*$ && "$steps" =~ ^[1-9][0-9]*$ ]] ||
  { echo "weak_scaling: WEAK_CELLS_PER_EDGE and WEAK_STEPS must be positive integers" >&2; exit 2; }
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
cores=$(getconf _NPROCESSORS_ONLN)  # (nproc would count OMP_NUM_THREADS)

# The process grid of a rank count: factors of 2 dealt to x, y, z in turn
# (then any odd factor to x), so that every rank holds an n x n x n block.
grid_of() {
  local r=$1 g=(1 1 1) axis=0
  while [ $((r % 2)) -eq 0 ]; do g[$axis]=$((g[axis] * 2)); r=$((r / 2)); axis=$(((axis + 1) % 3)); done
  g[0]=$((g[0] * r))
  echo "${g[0]} ${g[1]} ${g[2]}"
}

echo "ranks,grid,cells,cells_per_rank,steps,wall_seconds,halo_seconds,setup_total,setup_generate,setup_sample,setup_decompose,setup_initialize,peak_max,peak_mean,halo_bytes_per_step,halo_messages_per_step,reductions_per_step,ranks_per_core" > "$out/results.csv"
for ranks in $rank_counts; do
  read -r gx gy gz < <(grid_of "$ranks")
  dir=$out/run_$ranks
  rm -rf "$dir"
  status=0
  mpiexec -np "$ranks" --bind-to none "$exe" --problem sedov \
    --set mesh.nx=$((gx * edge)) --set mesh.ny=$((gy * edge)) --set mesh.nz=$((gz * edge)) \
    --set numerics.max_steps="$steps" --quiet --output "$dir" > "$dir.log" 2>&1 || status=$?
  # the step limit ends the run on purpose (exit code 3, "max_steps reached")
  if ! grep -q "max_steps reached" "$dir.log" || [ ! -f "$dir/summary.json" ]; then
    echo "weak_scaling: $ranks ranks failed (exit $status):" >&2; cat "$dir.log" >&2; exit 1
  fi
  /usr/bin/python3 - "$dir/summary.json" "$ranks" "${gx}x${gy}x${gz}" "$cores" >> "$out/results.csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
ranks, grid, cores = int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
setup, memory, halo = s["setup_seconds"], s["memory"], s["halo"]
row = [ranks, grid, s["cells"], s["cells"] // ranks, s["steps"], s["wall_seconds"],
       s["phase_seconds"].get("halo", 0.0), setup["total"], setup["generate"],
       setup["sample_materials"], setup["decompose"], setup["initialize"],
       memory["peak_bytes"]["max"], memory["peak_bytes"]["mean"], halo["bytes_per_step"],
       halo["messages_per_step"], halo["reductions_per_step"], max(1.0, ranks / cores)]
print(",".join(str(v) for v in row))
PY
done
/usr/bin/python3 - "$out/results.csv" <<'PY' | tee "$out/table.md"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
base = None
print("| ranks | grid | cells | time/step [ms] | efficiency | halo share | set-up [s] (generate / sample / decompose / initialize) | peak per rank, max [MB] | halo [MB/step] | messages/step | ranks per core |")
print("|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|")
for r in rows:
    step = float(r["wall_seconds"]) / int(r["steps"])
    base = base or step
    print("| %s | %s | %s | %.1f | %.2f | %.1f%% | %.2f (%.2f / %.2f / %.2f / %.2f) | %.0f | %.2f | %.0f | %.1f |" % (
        r["ranks"], r["grid"], r["cells"], 1e3 * step, base / step,
        100 * float(r["halo_seconds"]) / float(r["wall_seconds"]), float(r["setup_total"]),
        float(r["setup_generate"]), float(r["setup_sample"]), float(r["setup_decompose"]),
        float(r["setup_initialize"]), float(r["peak_max"]) / 1e6,
        float(r["halo_bytes_per_step"]) / 1e6, float(r["halo_messages_per_step"]),
        float(r["ranks_per_core"])))
PY
echo "cells per rank: ${edge}^3; ${steps} steps; one thread per rank on a ${cores}-core machine" | tee -a "$out/table.md"
