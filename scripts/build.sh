#!/usr/bin/env bash
# Configures (Release) and builds lagremap in build/ against the Kokkos that
# scripts/setup.sh prepared (or the user's Kokkos_ROOT). Used by run.sh/test.sh.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}
kokkos_root=${Kokkos_ROOT:-$(cat "$build/kokkos-root.txt" 2>/dev/null || true)}
[ -n "$kokkos_root" ] || { echo "build: run scripts/setup.sh first (no Kokkos prefix known)" >&2; exit 1; }
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="$kokkos_root" >/dev/null
cmake --build "$build" -j "$(nproc)" "$@"
