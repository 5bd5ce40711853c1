#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, then configures, builds and
# runs tests/install_consumer against it as a new user would (a C++-only
# project, find_package(lagremap), <lagremap/...> includes).
#   check.sh BUILD_DIR WORK_DIR CXX_COMPILER
set -euo pipefail
build=$1 work=$2 cxx=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work.install.log" 2>&1 ||
  { cat "$work.install.log"; exit 1; }
kokkos_root=$(sed -n 's/^Kokkos_DIR:PATH=//p' "$build/CMakeCache.txt")
cmake -S "$here" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DKokkos_DIR="$kokkos_root"
cmake --build "$work/build" -j 2
OMP_NUM_THREADS=1 OMP_PROC_BIND=false "$work/build/consumer"
