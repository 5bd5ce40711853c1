#!/usr/bin/env bash
# The GPU check of the CUDA variant, for a machine with an NVIDIA GPU, nvcc,
# cmake and a host compiler but no Debian packages and no network.
#   1. on a machine like the developers' (Debian 12, packages reachable):
#        scripts/setup.sh --stage-device stage/      (Kokkos source + packages, < 60 MiB)
#   2. on the GPU machine, from the repository root:
#        scripts/device_check.sh [--stage DIR] [--report DIR] [--skip-gpu]
# It unpacks the stage, builds Kokkos 3.4.01 (CUDA + Serial, the arch of the GPU
# found by nvidia-smi, else LAGREMAP_CUDA_ARCH or 90) and every lagremap target
# against it, then on the GPU runs `sedov` (30^3 and 120^3), `taylor --mode
# remap --scale 0.5`, the paper's four remap cases (taylor, beam, ball, shell),
# the kernel benchmarks and the quick ctest set, and writes one report folder:
#   report/summary.txt      what ran, pass/fail, the nvidia-smi line, the kernels'
#                           registers, stack and spills, FOM lines (per phase too)
#   report/gpu_resources.txt  perf/gpu_resources.sh --check for the GPU's arch
#   report/ctest.txt        the quick tests' output
#   report/<case>.txt       each run's stdout and stderr
#   report/bench_*.json     per-kernel rates (Google Benchmark JSON)
# --skip-gpu (or no GPU found) builds everything and skips the GPU part, saying so.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
stage=$here/stage
report=$here/device-report
skip_gpu=0
while [ $# -gt 0 ]; do
  case "$1" in
    --stage) stage=${2:?--stage needs a directory}; shift 2 ;;
    --report) report=${2:?--report needs a directory}; shift 2 ;;
    --skip-gpu) skip_gpu=1; shift ;;
    *) echo "device_check: unknown argument '$1' (--stage DIR, --report DIR, --skip-gpu)" >&2; exit 2 ;;
  esac
done
work=${LAGREMAP_DEVICE_WORK:-${TMPDIR:-/tmp}/lagremap-device}
jobs=$(nproc)
mkdir -p "$report" "$work"
report=$(cd "$report" && pwd)
summary="$report/summary.txt"
: > "$summary"
say() { printf '%s\n' "$*" | tee -a "$summary"; }
die() { say "FAILED: $*"; exit 1; }

for f in kokkos-3.4.01-src.tar.gz debian-prefix.tar.xz; do
  [ -f "$stage/$f" ] || die "no $stage/$f (run scripts/setup.sh --stage-device $stage on a Debian 12 machine)"
done
command -v cmake >/dev/null || die "no cmake"
# shellcheck source=backend.sh
source "$here/scripts/backend.sh" --backend cuda || die "no nvcc"

gpu=0
if [ $skip_gpu -eq 0 ] && command -v nvidia-smi >/dev/null && nvidia-smi -L >/dev/null 2>&1; then
  gpu=1
  smi=$(nvidia-smi --query-gpu=name,compute_cap,driver_version,memory.total --format=csv,noheader | head -n 1)
  say "gpu: $smi"
  cap=$(echo "$smi" | cut -d, -f2 | tr -d ' .')
  [ -n "${LAGREMAP_CUDA_ARCH:-}" ] || cuda_arch=$cap
else
  say "gpu: none used ($([ $skip_gpu -eq 1 ] && echo '--skip-gpu' || echo 'no nvidia-smi or no device')): the GPU part is skipped"
fi
export NVCC_WRAPPER_DEFAULT_ARCH=sm_$cuda_arch
say "nvcc: $("$nvcc_bin" --version | tail -n 1), arch sm_$cuda_arch, host $(${CXX:-g++} --version | head -n 1)"

# --- the stage
prefix="$work/prefix"
if [ ! -f "$prefix/.unpacked" ]; then
  rm -rf "$prefix" "$work/kokkos-src"
  mkdir -p "$prefix" "$work/kokkos-src"
  tar -xJf "$stage/debian-prefix.tar.xz" -C "$prefix" || die "unpacking the Debian prefix"
  tar -xzf "$stage/kokkos-3.4.01-src.tar.gz" -C "$work/kokkos-src" || die "unpacking Kokkos"
  touch "$prefix/.unpacked"
fi
lib="$prefix/usr/lib/x86_64-linux-gnu"
export LD_LIBRARY_PATH="$lib:$lib/openmpi/lib:$lib/hdf5/openmpi${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# Open MPI relocated to the prefix: its wrapper data, help files and plugins.
export OPAL_PREFIX="$prefix/usr" OPAL_LIBDIR="$lib/openmpi/lib"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Its PMIx looks for plugins where Debian puts them; a machine with a PMIx of
# its own there has plugins of another version (their load errors went to
# every run's stderr): the staged ones.
export PMIX_MCA_mca_base_component_path="$lib/pmix2/lib/pmix" PMIX_MCA_pcompress_base_silence_warning=1
# CMake runs of the tests (the installed package's consumer) find the staged packages.
export CMAKE_PREFIX_PATH="$prefix/usr:$lib/cmake${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"

# --- Kokkos (CUDA + Serial) from the staged, patched source
src="$work/kokkos-src/kokkos-3.4.01"
cuda_options=$(kokkos_cuda_options "$src" "$cuda_arch") || die "no Kokkos 3.4.01 arch for sm_$cuda_arch"
kokkos="$work/kokkos-sm$cuda_arch"
if [ ! -f "$kokkos/lib/cmake/Kokkos/KokkosConfig.cmake" ]; then
  # shellcheck disable=SC2086  # the options are words without spaces
  cmake -S "$src" -B "$work/kokkos-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$kokkos" -DCMAKE_CXX_STANDARD=17 $cuda_options \
    -DKokkos_ENABLE_TESTS=OFF -DBUILD_SHARED_LIBS=OFF \
    > "$report/kokkos-build.txt" 2>&1 &&
    cmake --build "$work/kokkos-build" -j "$jobs" >> "$report/kokkos-build.txt" 2>&1 &&
    cmake --install "$work/kokkos-build" >> "$report/kokkos-build.txt" 2>&1 ||
    die "Kokkos build (report/kokkos-build.txt)"
fi
say "kokkos: 3.4.01 CUDA+Serial $(echo "$cuda_options" | grep -o 'Kokkos_ARCH_[A-Z0-9]*') in $kokkos"

# --- lagremap, every target, against the stage. No compiler wrappers: the
# staged mpicc and h5pcc carry Debian's /usr paths, so the MPI and HDF5
# locations go to CMake directly (an h5pcc that does not exist makes FindHDF5
# take the given include directory and library), and pkg-config, whose .pc
# files say the same, is kept out.
build="$work/build-cuda"
rm -f "$build/CMakeCache.txt"  # every location found anew, none cached from another run
t0=$(date +%s)
PKG_CONFIG_LIBDIR=/nonexistent PKG_CONFIG_PATH= \
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="$kokkos" \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DCMAKE_CXX_COMPILER="$kokkos/bin/nvcc_wrapper" \
  -DCMAKE_PREFIX_PATH="$prefix/usr;$lib/cmake" \
  -DMPI_SKIP_COMPILER_WRAPPER=ON -DMPI_C_HEADER_DIR="$lib/openmpi/include" \
  -DMPI_CXX_HEADER_DIR="$lib/openmpi/include" -DMPI_C_LIB_NAMES=mpi -DMPI_CXX_LIB_NAMES=mpi \
  -DMPI_C_ADDITIONAL_INCLUDE_DIRS="$lib/openmpi/include/openmpi" \
  -DMPI_CXX_ADDITIONAL_INCLUDE_DIRS="$lib/openmpi/include/openmpi" \
  -DMPI_mpi_LIBRARY="$lib/openmpi/lib/libmpi.so" -DMPIEXEC_EXECUTABLE="$prefix/usr/bin/orterun" \
  -DHDF5_C_COMPILER_EXECUTABLE="$prefix/no-wrapper/h5pcc" \
  -DHDF5_C_INCLUDE_DIR="$prefix/usr/include/hdf5/openmpi" \
  -DHDF5_hdf5_LIBRARY_RELEASE="$lib/hdf5/openmpi/libhdf5.so" \
  > "$report/configure.txt" 2>&1 || die "configure (report/configure.txt)"
cmake --build "$build" -j "$jobs" > "$report/build.txt" 2>&1 || die "build (report/build.txt)"
warnings=$(grep -c -i 'warning' "$report/build.txt" || true)
say "build: every target in $(($(date +%s) - t0)) s, $warnings warning lines (report/build.txt)"
if [ -x "$CUDA_ROOT/bin/cuobjdump" ]; then
  say "gpu code of lagremap: $("$CUDA_ROOT/bin/cuobjdump" --list-elf "$build/lagremap" | head -n 1)"
elif command -v python3 >/dev/null; then
  say "gpu code of lagremap: $(python3 "$here/scripts/cuda_arches.py" "$build/lagremap" | paste -sd ';')"
fi

# registers, stack and spills per kernel for this arch (perf/gpu_resources.sh;
# the bounds are sm_90's)
LAGREMAP_BUILD_DIR="$build" Kokkos_ROOT="$kokkos" bash "$here/perf/gpu_resources.sh" --check \
  "$cuda_arch" > "$report/gpu_resources.txt" 2>&1 || true
say "gpu resources (report/gpu_resources.txt):"
grep -v "^gpu_resources: [a-z]*/" "$report/gpu_resources.txt" | sed 's/^/  /' | tee -a "$summary"

if [ $gpu -eq 0 ]; then
  say "GPU part skipped: nothing was run on a GPU"
  exit 0
fi

# --- on the GPU
status=0
run_case() {
  local name=$1
  shift
  local t0 rc=0
  t0=$(date +%s%N)
  timeout 300 "$build/lagremap" "$@" --output "$work/out/$name" > "$report/$name.txt" 2>&1 || rc=$?
  say "$name (exit $rc, $((($(date +%s%N) - t0) / 1000000)) ms): $(grep '^lagremap:' "$report/$name.txt" | tail -n 1 | cut -d: -f2-)"
  say "  $(grep '^FOM' "$report/$name.txt" || echo 'no FOM line')"
  grep -E '^check .*FAIL' "$report/$name.txt" | sed 's/^/  /' | tee -a "$summary"
  # the FOM of each phase (summary.json: cell-steps per second of its kernels)
  python3 -c 'import json, sys
rates = json.load(open(sys.argv[1]))["cell_steps_per_second"]["phases"]
print("  per phase [cell-steps/s]: " + ", ".join(f"{k} {v:.3g}" for k, v in rates.items() if v > 0))' \
    "$work/out/$name/summary.json" 2>/dev/null | tee -a "$summary"
  [ $rc -eq 0 ] || status=1
}
run_case sedov --problem sedov
run_case taylor_remap_half --problem taylor --mode remap --scale 0.5
# a mesh that fills the GPU (120^3 cells, to a quarter of the blast's time), and
# the paper's four remap cases at its resolution
run_case sedov_120 --problem sedov --scale 4 --t-end 0.25
for case in taylor beam ball shell; do run_case "${case}_remap" --problem "$case" --mode remap; done

for bench in bench_lagrange bench_constitutive; do
  "$build/perf/$bench" --benchmark_min_time=0.2 --benchmark_format=json \
    --benchmark_out="$report/$bench.json" > "$report/$bench.txt" 2>&1 || status=1
  say "$bench: $(grep -c '"name"' "$report/$bench.json" 2>/dev/null || echo 0) benchmarks (report/$bench.json)"
  grep -E '^BM_' "$report/$bench.txt" | sed 's/^/  /' >> "$summary"
done
# The quick tests last (the numbers above come first): several at once, the
# GPU shared by their processes, half the cores (the MPI tests start ranks).
ctest_jobs=$(((jobs + 1) / 2))
t0=$(date +%s)
(cd "$build" && ctest -L quick -j "$ctest_jobs" --output-on-failure --timeout 600) > "$report/ctest.txt" 2>&1 || status=1
say "ctest quick ($ctest_jobs at a time, $(($(date +%s) - t0)) s): $(grep -E 'tests passed|tests failed' "$report/ctest.txt" | tail -n 1)"
grep -E '^\s+[0-9]+ - ' "$report/ctest.txt" | sed 's/^/  failed: /' | tee -a "$summary"
say "status: $([ $status -eq 0 ] && echo 'all passed' || echo 'FAILURES above')"
exit $status
