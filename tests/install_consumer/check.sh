#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, then configures, builds and
# runs tests/install_consumer against it as a new user would (a C++-only
# project, find_package(lagremap), <lagremap/lagremap.hpp>). Also compiles
# one source that includes every installed header, and fails on a header
# left at the old place (include/lagremap/src/).
#   check.sh BUILD_DIR WORK_DIR CXX_COMPILER
set -euo pipefail
build=$1 work=$2 cxx=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work.install.log" 2>&1 ||
  { cat "$work.install.log"; exit 1; }
include=$work/prefix/include
[ -f "$include/lagremap/lagremap.hpp" ] ||
  { echo "check: no umbrella header $include/lagremap/lagremap.hpp" >&2; exit 1; }
[ ! -e "$include/lagremap/src" ] ||
  { echo "check: headers installed under $include/lagremap/src/ (src/ belongs at the top)" >&2; exit 1; }
all_headers=$work/all_headers.cpp
(cd "$include" && find lagremap -name '*.hpp' | LC_ALL=C sort | sed 's/.*/#include <&>/') > "$all_headers"
echo "check: $(wc -l < "$all_headers") installed headers"
kokkos_root=$(sed -n 's/^Kokkos_DIR:PATH=//p' "$build/CMakeCache.txt")
cmake -S "$here" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DKokkos_DIR="$kokkos_root" \
  -DLAGREMAP_ALL_HEADERS_SOURCE="$all_headers"
cmake --build "$work/build" -j 2
OMP_NUM_THREADS=1 OMP_PROC_BIND=false "$work/build/consumer"
