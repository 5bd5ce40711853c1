#!/usr/bin/env bash
# The README's test command: installs what is missing, builds (Release) and runs
# the tests with ctest. By default the quick set (ctest label "quick");
#   LAGREMAP_TEST_LABELS=long scripts/test.sh   the long physics runs,
#   LAGREMAP_TEST_LABELS=all  scripts/test.sh   everything.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LAGREMAP_BUILD_DIR:-$here/build}

bash "$here/scripts/setup.sh"
bash "$here/scripts/build.sh"

# Kokkos' advice for unit tests; two threads, the machine's cores.
export OMP_PROC_BIND=false OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
labels=${LAGREMAP_TEST_LABELS:-quick}
cd "$build"
if [ "$labels" = all ]; then
  ctest --output-on-failure --timeout 1200
else
  ctest --output-on-failure --timeout 1200 -L "$labels"
fi
