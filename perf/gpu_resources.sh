#!/usr/bin/env bash
# Registers, stack frame and spills per lagremap kernel on the GPU, without a
# GPU: compiles the translation units that launch kernels with the CUDA
# Kokkos prefix's nvcc_wrapper and -Xptxas=-v, and tabulates ptxas's report
# per kernel (perf/gpu_resources.py; docs/performance.md).
#   perf/gpu_resources.sh [--check] [ARCH] [SOURCE...]
#     --check: also fail (exit 1) where a kernel passes its bounds in
#             perf/gpu_resource_bounds.txt (128 registers, 256 B stack, no
#             spill, unless the file names the kernel); CI's CUDA compile
#             check runs it
#     ARCH: the sm_ number (default: the prefix's, LAGREMAP_CUDA_ARCH or 90)
#     SOURCE: translation units (default: every src/ and problems/ source
#             that launches a kernel)
# Needs scripts/setup.sh --backend cuda first (or Kokkos_ROOT naming a CUDA
# Kokkos prefix); about 25 s per translation unit on 2 cores. Where the CUDA
# build tree (build-cuda/, or LAGREMAP_BUILD_DIR) has compile_commands.json,
# each unit is compiled with its own command from it (and the build's arch).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
check=()
if [ "${1:-}" = --check ]; then
  check=(--bounds "$here/perf/gpu_resource_bounds.txt")
  shift
fi
arch=${1:-${LAGREMAP_CUDA_ARCH:-90}}
shift || true
kokkos_root=${Kokkos_ROOT:-$(cat "$here/build-cuda/kokkos-root.txt" 2>/dev/null || true)}
wrapper="$kokkos_root/bin/nvcc_wrapper"
[ -x "$wrapper" ] || {
  echo "gpu_resources: no CUDA Kokkos prefix (run scripts/setup.sh --backend cuda and scripts/build.sh --backend cuda, or set Kokkos_ROOT)" >&2
  exit 2
}
if [ $# -gt 0 ]; then
  sources=("$@")
else
  mapfile -t sources < <(cd "$here" && grep -l -E "parallel_|kernels/|_step\.hpp" src/*.cpp problems/*.cpp)
fi
python=/usr/bin/python3
[ -x "$python" ] || python=python3
# A CUDA build tree's compile commands, where it has them (scripts/build.sh
# --backend cuda and scripts/device_check.sh export them): the exact flags of
# each translation unit. Otherwise the project's CUDA flags (CMakeLists.txt).
commands=${LAGREMAP_BUILD_DIR:-$here/build-cuda}/compile_commands.json
compile_command() {  # the command compiling $1 (a path under the repository)
  "$python" - "$commands" "$here/$1" <<'PY'
import json, shlex, sys
for entry in json.load(open(sys.argv[1])):
    if entry["file"] == sys.argv[2]:
        words, kept = shlex.split(entry["command"]), []
        while words:  # the object to /dev/null, no dependency file
            word = words.pop(0)
            if word in ("-o", "-MT", "-MF"):
                value = words.pop(0)
                if word == "-o":
                    kept += ["-o", "/dev/null"]
            elif word != "-MD":
                kept.append(word)
        words = kept
        print(entry["directory"])
        print("\n".join(words))
        break
PY
}
mpi_includes=$(mpicxx --showme:incdirs 2>/dev/null | sed 's/\([^ ]*\)/-isystem \1/g' || true)
report=$(mktemp)
trap 'rm -f "$report"' EXIT
for source in "${sources[@]}"; do
  echo "gpu_resources: $source" >&2
  found=$([ -f "$commands" ] && compile_command "$source" || true)
  if [ -n "$found" ]; then
    directory=$(echo "$found" | head -n 1)
    mapfile -t words < <(echo "$found" | tail -n +2)
    (cd "$directory" && "${words[@]}" -Xptxas=-v) >>"$report" 2>&1 ||
      { echo "gpu_resources: $source did not compile:" >&2; tail -20 "$report" >&2; exit 1; }
    continue
  fi
  # the project's CUDA flags (CMakeLists.txt), the arch asked for, ptxas verbose
  # shellcheck disable=SC2086
  "$wrapper" -DKOKKOS_DEPENDENCE -I"$here" -isystem "$kokkos_root/include" $mpi_includes \
    -isystem /usr/include/hdf5/openmpi -O3 -DNDEBUG -fno-math-errno -ffp-contract=off \
    --fmad=false -expt-extended-lambda -arch="sm_$arch" -std=c++17 -Xptxas=-v \
    -c "$here/$source" -o /dev/null >>"$report" 2>&1 ||
    { echo "gpu_resources: $source did not compile:" >&2; tail -20 "$report" >&2; exit 1; }
done
"$python" "$here/perf/gpu_resources.py" "${check[@]+"${check[@]}"}" "$report"
