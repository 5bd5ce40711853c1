#!/usr/bin/env bash
# Installs what lagremap needs, idempotently:
#  - Debian packages (compiler, cmake, Open MPI, parallel HDF5, GoogleTest,
#    Google Benchmark, CLI11, toml++, python3 numpy/matplotlib/h5py);
#  - Kokkos 3.4.01, built from Debian's trilinos source package into a cached
#    prefix, unless the user supplies Kokkos_ROOT:
#      --backend openmp (default)  OpenMP + Serial, as shipped;
#      --backend cuda              CUDA + Serial for LAGREMAP_CUDA_ARCH (default 90),
#                                  from a copy of the source with the project's
#                                  patch scripts/patches/kokkos-3.4.01-cuda.patch;
#    (LAGREMAP_BACKEND=cuda is the same as --backend cuda).
#  - --stage-device DIR: also stages in DIR what scripts/device_check.sh needs on
#    a GPU machine without Debian packages or network (see stage_device below).
# Prints nothing but progress; the Kokkos prefix is written to
# build/kokkos-root.txt (build-cuda/ for cuda) for the other scripts.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=backend.sh
source "$here/scripts/backend.sh"
stage_dir=""
set -- "${backend_args[@]+"${backend_args[@]}"}"
while [ $# -gt 0 ]; do
  case "$1" in
    --stage-device) stage_dir=${2:?--stage-device needs a directory}; shift 2 ;;
    --stage-device=*) stage_dir=${1#--stage-device=}; shift ;;
    *) echo "setup: unknown argument '$1' (--backend openmp|cuda, --stage-device DIR)" >&2; exit 2 ;;
  esac
done
cache=${LAGREMAP_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/lagremap}
# The CUDA build's source and prefix carry the patch's checksum: a changed
# patch gives a new patched copy and a new build, never a stale one.
cuda_patch="$here/scripts/patches/kokkos-3.4.01-cuda.patch"
cuda_patch_id=$(sha256sum "$cuda_patch" | cut -c1-8)
if [ "$backend" = cuda ]; then
  kokkos_prefix_default="$cache/kokkos-3.4.01-cuda-sm$cuda_arch-$cuda_patch_id"
else
  kokkos_prefix_default="$cache/kokkos-3.4.01-openmp"
fi

log() { printf '[setup] %s\n' "$*" >&2; }

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

packages=(
  g++ cmake make pkg-config dpkg-dev patch
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev
  python3-numpy python3-matplotlib python3-h5py
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
apt_updated=0
apt_update_once() {
  if [ $apt_updated -eq 0 ]; then
    "${sudo_cmd[@]}" apt-get update -qq
    apt_updated=1
  fi
}
if [ ${#missing[@]} -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  apt_update_once
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# --- Kokkos -----------------------------------------------------------------
kokkos_found() { [ -f "$1/lib/cmake/Kokkos/KokkosConfig.cmake" ] || [ -f "$1/lib64/cmake/Kokkos/KokkosConfig.cmake" ]; }

# Debian's trilinos source package, downloaded once; prints packages/kokkos.
kokkos_source() {
  local src_list=/etc/apt/sources.list.d/lagremap-deb-src.sources
  local work="$cache/trilinos-src"
  mkdir -p "$work"
  if ! compgen -G "$work/*/packages/kokkos" >/dev/null; then
    if ! grep -rqs '^Types:.*deb-src' /etc/apt/sources.list.d/ && ! grep -qs '^deb-src' /etc/apt/sources.list; then
      # Same archives as the binary entries, source type (the deb822 file Debian ships).
      sed -e 's/^Types:.*/Types: deb-src/' /etc/apt/sources.list.d/debian.sources | "${sudo_cmd[@]}" tee "$src_list" >/dev/null
      apt_updated=0
    fi
    apt_update_once >&2
    (cd "$work" && apt-get source --download-only trilinos >/dev/null 2>&1)
    local tarball top
    tarball=$(ls "$work"/trilinos_*.orig.tar.* | head -n 1)
    log "extracting packages/kokkos from $(basename "$tarball")"
    # (no pipefail here: head closes the pipe early on purpose)
    top=$(set +o pipefail; tar -tf "$tarball" | head -n 1 | cut -d/ -f1)
    tar -xf "$tarball" -C "$work" "$top/packages/kokkos"
  fi
  ls -d "$work"/*/packages/kokkos | head -n 1
}

# A copy of the Kokkos source for the CUDA build with the project's patch
# applied (once: a copy already patched is kept); prints its path.
patched_cuda_source() {
  local shipped=$1 patched="$cache/kokkos-3.4.01-cuda-src-$cuda_patch_id"
  local patch_file=$cuda_patch
  if [ ! -f "$patched/.lagremap-patched" ]; then
    rm -rf "$patched"
    cp -r "$shipped" "$patched"
    if ! patch -d "$patched" -p1 --dry-run -R -s -f < "$patch_file" >/dev/null 2>&1; then
      patch -d "$patched" -p1 -s -f < "$patch_file" >&2
    fi
    touch "$patched/.lagremap-patched"
  fi
  echo "$patched"
}


if [ -n "${Kokkos_ROOT:-}" ]; then
  kokkos_found "$Kokkos_ROOT" || { echo "setup: Kokkos_ROOT=$Kokkos_ROOT has no KokkosConfig.cmake" >&2; exit 1; }
  kokkos_prefix=$Kokkos_ROOT
  log "using user-supplied Kokkos_ROOT=$kokkos_prefix"
else
  kokkos_prefix=$kokkos_prefix_default
  if kokkos_found "$kokkos_prefix"; then
    log "reusing Kokkos in $kokkos_prefix"
  else
    log "building Kokkos 3.4.01 ($backend) from Debian's trilinos source package"
    kokkos_src=$(kokkos_source)
    build="$cache/kokkos-build-$backend"
    rm -rf "$build"
    if [ "$backend" = cuda ]; then
      kokkos_src=$(patched_cuda_source "$kokkos_src")
      cuda_options=$(kokkos_cuda_options "$kokkos_src" "$cuda_arch") || exit 2
      # shellcheck disable=SC2086  # the options are words without spaces
      cmake -S "$kokkos_src" -B "$build" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_INSTALL_PREFIX="$kokkos_prefix" -DCMAKE_CXX_STANDARD=17 $cuda_options \
        -DKokkos_ENABLE_TESTS=OFF -DKokkos_ENABLE_EXAMPLES=OFF \
        -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON >/dev/null
    else
      cmake -S "$kokkos_src" -B "$build" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_INSTALL_PREFIX="$kokkos_prefix" -DCMAKE_CXX_STANDARD=17 \
        -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_SERIAL=ON \
        -DKokkos_ENABLE_TESTS=OFF -DKokkos_ENABLE_EXAMPLES=OFF \
        -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON >/dev/null
    fi
    cmake --build "$build" -j "$(nproc)" >/dev/null
    cmake --install "$build" >/dev/null
    rm -rf "$build"
    kokkos_found "$kokkos_prefix" || { echo "setup: Kokkos build did not install a KokkosConfig.cmake" >&2; exit 1; }
  fi
fi

mkdir -p "$build_dir"
echo "$kokkos_prefix" > "$build_dir/kokkos-root.txt"
log "ready (backend $backend, Kokkos_ROOT=$kokkos_prefix)"

if [ -n "$stage_dir" ]; then
  # shellcheck source=stage_device.sh
  source "$here/scripts/stage_device.sh"
  stage_device "$stage_dir"
fi
