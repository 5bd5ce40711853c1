# Sourced by setup.sh, build.sh and device_check.sh: the Kokkos backend of a
# build and where its files go.
#   --backend openmp|cuda (or LAGREMAP_BACKEND; default openmp)
#   LAGREMAP_CUDA_ARCH    compute capability of the CUDA build, default 90 (Hopper)
# Sets: backend, cuda_arch, build_dir (build/ or build-cuda/), nvcc_bin (cuda only),
# and leaves the remaining arguments in backend_args.

backend=${LAGREMAP_BACKEND:-openmp}
backend_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --backend) backend=${2:?--backend needs a value (openmp or cuda)}; shift 2 ;;
    --backend=*) backend=${1#--backend=}; shift ;;
    *) backend_args+=("$1"); shift ;;
  esac
done
case "$backend" in
  openmp | cuda) ;;
  *) echo "unknown backend '$backend' (openmp or cuda)" >&2; exit 2 ;;
esac
cuda_arch=${LAGREMAP_CUDA_ARCH:-90}
case "$cuda_arch" in
  ''|*[!0-9]*) echo "LAGREMAP_CUDA_ARCH='$cuda_arch' is not a compute capability such as 90 or 80" >&2; exit 2 ;;
esac

if [ "$backend" = cuda ]; then
  build_dir=${LAGREMAP_BUILD_DIR:-$here/build-cuda}
else
  build_dir=${LAGREMAP_BUILD_DIR:-$here/build}
fi

# Kokkos' name of a CUDA compute capability (Kokkos_ARCH_<name>); fails for
# one Kokkos 3.4.01 does not know.
kokkos_cuda_arch_name() {
  case "$1" in
    70) echo VOLTA70 ;;
    72) echo VOLTA72 ;;
    75) echo TURING75 ;;
    80) echo AMPERE80 ;;
    86) echo AMPERE86 ;;
    90) echo HOPPER90 ;;  # added to 3.4.01 by scripts/patches/kokkos-3.4.01-cuda.patch
    *) echo "compute capability $1: Kokkos 3.4.01 knows 70 72 75 80 86 (90 with the project patch)" >&2
       return 1 ;;
  esac
}

# CMake options of a Kokkos CUDA + Serial build from the (patched) source SRC
# for compute capability ARCH:  kokkos_cuda_options SRC ARCH
kokkos_cuda_options() {
  local name
  name=$(kokkos_cuda_arch_name "$2") || return 1
  echo "-DCMAKE_CXX_COMPILER=$1/bin/nvcc_wrapper -DKokkos_ENABLE_CUDA=ON -DKokkos_ENABLE_SERIAL=ON" \
    "-DKokkos_ENABLE_CUDA_LAMBDA=ON -DKokkos_ARCH_$name=ON"
}

# nvcc on PATH, else the toolkit's usual place.
find_nvcc() {
  if command -v nvcc >/dev/null 2>&1; then
    command -v nvcc
  elif [ -x /usr/local/cuda/bin/nvcc ]; then
    echo /usr/local/cuda/bin/nvcc
  fi
}

if [ "$backend" = cuda ]; then
  nvcc_bin=$(find_nvcc)
  [ -n "$nvcc_bin" ] || { echo "backend cuda: no nvcc on PATH or in /usr/local/cuda/bin" >&2; exit 1; }
  # nvcc_wrapper calls $CUDA_ROOT/bin/nvcc; sm_XX is its default arch for
  # compiles that come before Kokkos' own -arch (CMake's compiler checks).
  export CUDA_ROOT=${CUDA_ROOT:-$(dirname "$(dirname "$nvcc_bin")")}
  export PATH="$CUDA_ROOT/bin:$PATH"
  export NVCC_WRAPPER_DEFAULT_ARCH=sm_$cuda_arch
fi
