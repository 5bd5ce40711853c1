#!/usr/bin/env bash
# The README's run command: installs what is missing, builds (Release), runs
# lagremap and draws the plots of its output directory.
#   scripts/run.sh                       the headline case: taylor in remap mode (the
#                                        aluminium bar in gas) at half resolution into
#                                        out/taylor, and its lagrange reference at the
#                                        same cell size into out/taylor_lagrange, then
#                                        the overlays (lagrange solid, remap dashed);
#                                        about 25 s on 2 cores once built
#   scripts/run.sh --problem sedov ...   any lagremap arguments
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}

bash "$here/scripts/setup.sh"
bash "$here/scripts/build.sh" --target lagremap
export OMP_PROC_BIND=${OMP_PROC_BIND:-spread} OMP_PLACES=${OMP_PLACES:-threads}

# Plots of a run directory, also for a failed run (its last good state is
# written); not for bad input (status 2), which wrote nothing. A plot that
# fails sets plot_status (the exit status when the runs succeeded).
plot_status=0
plot() {
  local dir=$1 run_status=$2
  shift 2
  if [ -f "$dir/summary.json" ] && [ "$run_status" -ne 2 ]; then
    /usr/bin/python3 "$here/scripts/plot.py" "$dir" "$@" || plot_status=$?
  fi
}

if [ $# -eq 0 ]; then
  # Same cell size in both modes: --scale 0.5 gives 110 x 40 cells on the
  # 5.5 x 2 remap box and 100 x 20 on the 5 x 1 bar.
  remap_status=0 lagrange_status=0
  "$build/lagremap" --problem taylor --mode remap --scale 0.5 --output out/taylor ||
    remap_status=$?
  "$build/lagremap" --problem taylor --mode lagrange --scale 0.5 --output out/taylor_lagrange ||
    lagrange_status=$?
  plot out/taylor_lagrange $lagrange_status --no-compare
  if [ $lagrange_status -eq 2 ]; then
    plot out/taylor $remap_status --no-compare
  else
    plot out/taylor $remap_status --compare out/taylor_lagrange
  fi
  if [ -f out/taylor/comparison.md ]; then cat out/taylor/comparison.md; fi
  for status in $remap_status $lagrange_status $plot_status; do
    if [ "$status" -ne 0 ]; then exit "$status"; fi
  done
  exit 0
fi

args=("$@")
# Find the problem and output directory the run will use, to plot them.
problem="" output=""
for ((i = 0; i < ${#args[@]}; ++i)); do
  case "${args[$i]}" in
    --problem) problem=${args[$((i + 1))]:-} ;;
    --problem=*) problem=${args[$i]#--problem=} ;;
    --output) output=${args[$((i + 1))]:-} ;;
    --output=*) output=${args[$i]#--output=} ;;
  esac
done
if [ -z "$output" ] && [ -n "$problem" ]; then
  output="out/$problem"
  args+=(--output "$output")
fi

status=0
"$build/lagremap" "${args[@]}" || status=$?
if [ -n "$output" ]; then plot "$output" $status; fi
if [ $status -ne 0 ]; then exit $status; fi
exit $plot_status
