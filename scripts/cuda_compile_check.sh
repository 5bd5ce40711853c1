#!/usr/bin/env bash
# The CUDA variant's compile check (CI runs it after the tests): sets up the
# CUDA Kokkos, builds every target into build-cuda/ (compile and link only:
# nothing runs, a GPU is not needed) and fails on any compiler warning from
# lagremap's own files or on an executable without code for the chosen arch
# (LAGREMAP_CUDA_ARCH, default 90), or on a kernel past its registers, stack
# or spill bound (perf/gpu_resources.sh --check). Without nvcc it says so and
# succeeds.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if ! command -v nvcc >/dev/null 2>&1 && [ ! -x /usr/local/cuda/bin/nvcc ]; then
  echo "CUDA compile check skipped: no nvcc on PATH or in /usr/local/cuda/bin"
  exit 0
fi
arch=${LAGREMAP_CUDA_ARCH:-90}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
start=$(date +%s)
bash "$here/scripts/setup.sh" --backend cuda
if ! bash "$here/scripts/build.sh" --backend cuda > "$log" 2>&1; then
  # (the build's own lines, not its progress; its last lines where it has
  # none: a failure must never end the check without a word)
  { grep -v '^\[' "$log" || tail -n 20 "$log"; } | tail -n 60 >&2
  echo "CUDA compile check FAILED: the build (above)" >&2
  exit 1
fi
# Warnings located in our sources (nvcc: "file(line): warning", g++: "file:line:col: warning").
ours=$(grep -E "^($here|\.\./|[a-z_]+/)[^ ]*(\([0-9]+\)|:[0-9]+:[0-9]+): warning" "$log" | grep -v "/.cache/" || true)
if [ -n "$ours" ]; then
  echo "$ours" >&2
  echo "CUDA compile check FAILED: $(echo "$ours" | wc -l) warnings from lagremap's sources" >&2
  exit 1
fi
# The embedded GPU code of every executable: cuobjdump where the toolkit has
# it, else our reader of the fat binaries (the CUDA wheels here ship none).
cuobjdump=$(dirname "$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)")/cuobjdump
has_arch() {
  if [ -x "$cuobjdump" ]; then
    "$cuobjdump" --list-elf "$1" 2>/dev/null | grep -q "sm_$arch"
  else
    /usr/bin/python3 "$here/scripts/cuda_arches.py" "$1" --require "sm_$arch" >/dev/null
  fi
}
build=${LAGREMAP_BUILD_DIR:-$here/build-cuda}
checked=0
for exe in "$build/lagremap" "$build"/tests/test_* "$build"/perf/bench_*; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  has_arch "$exe" || { echo "CUDA compile check FAILED: $exe has no sm_$arch code" >&2; exit 1; }
  checked=$((checked + 1))
done
# Registers, stack and spills of every lagremap kernel against
# perf/gpu_resource_bounds.txt (docs/building.md §4): a kernel that passes its
# bound fails the check, so a regression shows without a GPU.
if ! bash "$here/perf/gpu_resources.sh" --check "$arch" > "$log" 2>&1; then
  grep -v "^gpu_resources: [a-z]*/" "$log" >&2
  echo "CUDA compile check FAILED: GPU resources past their bounds (above)" >&2
  exit 1
fi
grep -v "^gpu_resources: [a-z]*/" "$log"
echo "CUDA compile check passed: every target built in $(($(date +%s) - start)) s, $checked executables hold sm_$arch code, no warning from our sources, every kernel within its GPU resource bound"
