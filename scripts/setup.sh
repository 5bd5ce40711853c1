#!/usr/bin/env bash
# Installs what lagremap needs, idempotently:
#  - Debian packages (compiler, cmake, Open MPI, parallel HDF5, GoogleTest,
#    Google Benchmark, CLI11, toml++, python3 numpy/matplotlib/h5py);
#  - Kokkos 3.4.01 (OpenMP + Serial), built from Debian's trilinos source
#    package into a cached prefix, unless the user supplies Kokkos_ROOT.
# Prints nothing but progress; the Kokkos prefix is written to
# build/kokkos-root.txt for the other scripts.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cache=${LAGREMAP_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/lagremap}
kokkos_prefix_default="$cache/kokkos-3.4.01-openmp"

log() { printf '[setup] %s\n' "$*" >&2; }

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

packages=(
  g++ cmake make pkg-config dpkg-dev
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

if [ -n "${Kokkos_ROOT:-}" ]; then
  kokkos_found "$Kokkos_ROOT" || { echo "setup: Kokkos_ROOT=$Kokkos_ROOT has no KokkosConfig.cmake" >&2; exit 1; }
  kokkos_prefix=$Kokkos_ROOT
  log "using user-supplied Kokkos_ROOT=$kokkos_prefix"
else
  kokkos_prefix=$kokkos_prefix_default
  if kokkos_found "$kokkos_prefix"; then
    log "reusing Kokkos in $kokkos_prefix"
  else
    log "building Kokkos 3.4.01 (OpenMP+Serial) from Debian's trilinos source package"
    src_list=/etc/apt/sources.list.d/lagremap-deb-src.sources
    if ! grep -rqs '^Types:.*deb-src' /etc/apt/sources.list.d/ && ! grep -qs '^deb-src' /etc/apt/sources.list; then
      # Same archives as the binary entries, source type (the deb822 file Debian ships).
      sed -e 's/^Types:.*/Types: deb-src/' /etc/apt/sources.list.d/debian.sources | "${sudo_cmd[@]}" tee "$src_list" >/dev/null
      apt_updated=0
    fi
    apt_update_once
    work="$cache/trilinos-src"
    mkdir -p "$work"
    if ! ls -d "$work"/trilinos-*/packages/kokkos >/dev/null 2>&1; then
      (cd "$work" && apt-get source --download-only trilinos >/dev/null 2>&1)
      tarball=$(ls "$work"/trilinos_*.orig.tar.* | head -n 1)
      log "extracting packages/kokkos from $(basename "$tarball")"
      # (no pipefail here: head closes the pipe early on purpose)
      top=$(set +o pipefail; tar -tf "$tarball" | head -n 1 | cut -d/ -f1)
      tar -xf "$tarball" -C "$work" "$top/packages/kokkos"
    fi
    kokkos_src=$(ls -d "$work"/*/packages/kokkos | head -n 1)
    build="$work/kokkos-build"
    rm -rf "$build"
    cmake -S "$kokkos_src" -B "$build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_INSTALL_PREFIX="$kokkos_prefix" -DCMAKE_CXX_STANDARD=17 \
      -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_SERIAL=ON \
      -DKokkos_ENABLE_TESTS=OFF -DKokkos_ENABLE_EXAMPLES=OFF \
      -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON >/dev/null
    cmake --build "$build" -j "$(nproc)" >/dev/null
    cmake --install "$build" >/dev/null
    rm -rf "$build"
    kokkos_found "$kokkos_prefix" || { echo "setup: Kokkos build did not install a KokkosConfig.cmake" >&2; exit 1; }
  fi
fi

mkdir -p "$here/build"
echo "$kokkos_prefix" > "$here/build/kokkos-root.txt"
log "ready (Kokkos_ROOT=$kokkos_prefix)"
