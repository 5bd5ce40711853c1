#!/usr/bin/env bash
# Strong scaling of the whole code (docs/method.md §7.5): one fixed problem run as
# 1 rank x 1 thread, 1 rank x 2 threads and 2 ranks x 1 thread (more with
# SCALING_CONFIGS), each a few times; prints cell-steps per second (the
# figure of merit of summary.json, time loop only), speed-up and parallel
# efficiency against 1 x 1, the share of time in the halo exchange, and
# draws perf/strong_scaling.png-like plots with perf/plot_scaling.py.
#
#   perf/strong_scaling.sh [OUT_DIR] [-- LAGREMAP ARGS...]
#     OUT_DIR  default: out/strong_scaling (table.md, results.csv, scaling.png)
#     LAGREMAP ARGS  the problem (default: --problem sedov --scale 1.3333 --t-end 0.15,
#                    40^3 cells, 292 steps; SCALING_CASE=rod: the 3D Taylor rod,
#                    --problem rod --t-end 10e-6, 12,100 cells on its body-fitted
#                    mesh, its first 10 us)
#   Environment: SCALING_CASE (sedov or rod, when no LAGREMAP ARGS are given),
#     SCALING_CONFIGS (default "1x1 1x2 2x1": ranks x threads),
#     SCALING_REPEATS (default 3; the table shows the best of the runs),
#     LAGREMAP_BUILD_DIR (default build/).
# Builds nothing: run scripts/build.sh first. Timings need a quiet machine:
# the other processes' CPU load during the runs is printed with the table.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}
out=$here/out/strong_scaling
if [ $# -gt 0 ] && [ "$1" != "--" ]; then out=$1; shift; fi
[ "${1:-}" = "--" ] && shift
problem_args=("$@")
if [ ${#problem_args[@]} -eq 0 ]; then
  case ${SCALING_CASE:-sedov} in
    sedov) problem_args=(--problem sedov --scale 1.3333 --t-end 0.15) ;;
    rod) problem_args=(--problem rod --t-end 10e-6) ;;
    *) echo "strong_scaling: SCALING_CASE must be sedov or rod" >&2; exit 2 ;;
  esac
fi
configs=${SCALING_CONFIGS:-1x1 1x2 2x1}
repeats=${SCALING_REPEATS:-3}
exe=$build/lagremap
[ -x "$exe" ] || { echo "strong_scaling: no $exe (run scripts/build.sh first)" >&2; exit 1; }
mkdir -p "$out"
# Open MPI as root on a small machine: allowed, and as many ranks as asked.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Placement: each rank bound to its own `threads` cores (Open MPI's default
# binds a rank to one core, which would put all the threads of a 1-rank run
# on that core; unbound ranks get moved about and wait on each other).
export OMP_PROC_BIND=false

# Load of the machine during the runs: busy CPU seconds not spent by us.
busy_ticks() { local f; f=($(head -1 /proc/stat)); echo $((f[1] + f[2] + f[3] + f[6] + f[7] + f[8])); }
own_ticks() { awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat; }
start_busy=$(busy_ticks)
start_own=$(own_ticks)
start_time=$(date +%s)
echo "config,ranks,threads,run,cell_steps_per_second,wall_seconds,halo_seconds,steps,cells" > "$out/results.csv"
for config in $configs; do
  ranks=${config%x*}
  threads=${config#*x}
  for run in $(seq 1 "$repeats"); do
    dir=$out/run_${config}_$run
    rm -rf "$dir"
    # Exit code 1 (a check missed: the run is cut short on purpose) is fine.
    status=0
    OMP_NUM_THREADS=$threads mpiexec -np "$ranks" --map-by "slot:PE=$threads" --bind-to core "$exe" "${problem_args[@]}" --quiet \
      --output "$dir" > "$dir.log" 2>&1 || status=$?
    if [ "$status" -gt 1 ] || [ ! -f "$dir/summary.json" ]; then
      echo "strong_scaling: $config failed (exit $status):"; cat "$dir.log"; exit 1
    fi
    /usr/bin/python3 - "$dir/summary.json" "$config" "$ranks" "$threads" "$run" >> "$out/results.csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(",".join(sys.argv[2:6] + [str(s["cell_steps_per_second"]["total"]), str(s["wall_seconds"]),
      str(s["phase_seconds"].get("halo", 0.0)), str(s["steps"]), str(s["cells"])]))
PY
  done
done
other=$(( $(busy_ticks) - start_busy - ($(own_ticks) - start_own) ))
elapsed=$(( $(date +%s) - start_time + 1 ))
/usr/bin/python3 "$here/perf/plot_scaling.py" "$out/results.csv" "$out/scaling.png" | tee "$out/table.md"
echo "problem: ${problem_args[*]}" | tee -a "$out/table.md"
/usr/bin/python3 -c "print('other processes kept %.2f cores busy on average during the runs' % ($other / $(getconf CLK_TCK) / $elapsed))" | tee -a "$out/table.md"
