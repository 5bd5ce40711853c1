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
