#!/usr/bin/env bash
# Configures (Release) and builds lagremap against the Kokkos that
# scripts/setup.sh prepared (or the user's Kokkos_ROOT). Used by run.sh/test.sh.
#   scripts/build.sh [--backend openmp|cuda] [cmake --build arguments...]
#     openmp (default): into build/;
#     cuda: every target into build-cuda/, compiled by the Kokkos prefix's
#           nvcc_wrapper (LAGREMAP_BACKEND=cuda is the same).
# LAGREMAP_BUILD_DIR overrides the build directory.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=backend.sh
source "$here/scripts/backend.sh"
build=$build_dir
kokkos_root=${Kokkos_ROOT:-$(cat "$build/kokkos-root.txt" 2>/dev/null || true)}
[ -n "$kokkos_root" ] || {
  echo "build: run scripts/setup.sh${backend:+ --backend $backend} first (no Kokkos prefix known)" >&2
  exit 1
}
# -UKokkos_DIR: the Kokkos of this call, not one an earlier configure cached.
# (compile_commands.json: perf/gpu_resources.sh compiles each unit with its own flags)
configure=(-DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="$kokkos_root" -UKokkos_DIR
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
if [ "$backend" = cuda ]; then
  wrapper="$kokkos_root/bin/nvcc_wrapper"
  [ -x "$wrapper" ] || { echo "build: $kokkos_root has no bin/nvcc_wrapper (not a CUDA Kokkos?)" >&2; exit 1; }
  configure+=(-DCMAKE_CXX_COMPILER="$wrapper")
  # Another compiler than the cached one (a new Kokkos prefix): CMake would
  # drop the whole cache, and this call's -D options with it; start afresh.
  if [ -f "$build/CMakeCache.txt" ] &&
    ! grep -qx "CMAKE_CXX_COMPILER:[A-Z]*=$wrapper" "$build/CMakeCache.txt"; then
    rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
  fi
fi
cmake -S "$here" -B "$build" "${configure[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" "${backend_args[@]+"${backend_args[@]}"}"
