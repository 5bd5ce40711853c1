#!/usr/bin/env bash
# The README's run command: installs what is missing, builds (Release), runs
# lagremap and draws the plots of its output directory.
#   scripts/run.sh                       the headline case: taylor in remap mode (the
#                                        aluminium bar in gas) at half resolution,
#                                        about half a minute on 2 cores, into out/taylor
#   scripts/run.sh --problem sedov ...   any lagremap arguments
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}

bash "$here/scripts/setup.sh"
bash "$here/scripts/build.sh" --target lagremap

args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--problem taylor --mode remap --scale 0.5)
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

export OMP_PROC_BIND=${OMP_PROC_BIND:-spread} OMP_PLACES=${OMP_PLACES:-threads}
status=0
"$build/lagremap" "${args[@]}" || status=$?
# Plots also for a failed run (its last good state is written); not for bad input.
if [ -n "$output" ] && [ -f "$output/summary.json" ] && [ $status -ne 2 ]; then
  /usr/bin/python3 "$here/scripts/plot.py" "$output"
fi
exit $status
