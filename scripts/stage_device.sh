# Sourced by setup.sh for --stage-device DIR: stages, on a machine like this
# one (Debian 12, packages reachable), what scripts/device_check.sh needs on a
# GPU machine that has nvcc, cmake and a host compiler but no Debian packages
# and no network:
#   DIR/kokkos-3.4.01-src.tar.gz   Kokkos 3.4.01 with the project's CUDA patch applied;
#   DIR/debian-prefix.tar.xz       the Debian packages of Open MPI, parallel HDF5,
#                                  GoogleTest, Google Benchmark, CLI11 and toml++
#                                  unpacked into one prefix (usr/...), with every
#                                  shared library they load except the C and C++
#                                  runtimes the machine's compilers bring; static
#                                  libraries other than GoogleTest's and Benchmark's, Fortran
#                                  bindings and documentation left out;
#   DIR/MANIFEST.txt               the packages and versions, and the sizes.
# Needs the functions and variables of setup.sh (cache, log, kokkos_source,
# patched_cuda_source).

stage_packages=(
  libopenmpi-dev libopenmpi3 openmpi-bin openmpi-common
  libhdf5-openmpi-dev libhdf5-openmpi-103-1
  libgtest-dev libbenchmark-dev libbenchmark1debian
  libcli11-dev libtomlplusplus-dev libtomlplusplus3
)
# Provided by the target's own C/C++ toolchain: never staged.
stage_system_libs='^(libc|libm|libdl|libpthread|librt|libutil|libresolv|ld-linux-x86-64|libstdc\+\+|libgcc_s)\.so'
stage_limit_bytes=$((60 * 1024 * 1024))

stage_device() {
  local dir=$1
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  local work="$cache/stage-work"
  rm -rf "$work"
  mkdir -p "$work/debs" "$work/prefix"

  log "staging the patched Kokkos source"
  local src
  src=$(patched_cuda_source "$(kokkos_source)")
  tar -czf "$dir/kokkos-3.4.01-src.tar.gz" -C "$(dirname "$src")" \
    --transform "s|^$(basename "$src")|kokkos-3.4.01|" "$(basename "$src")"

  log "staging Debian packages: ${stage_packages[*]}"
  (cd "$work/debs" && apt-get download "${stage_packages[@]}" >/dev/null 2>&1) ||
    { apt_update_once >&2; (cd "$work/debs" && apt-get download "${stage_packages[@]}" >/dev/null); }
  local deb
  for deb in "$work"/debs/*.deb; do dpkg-deb -x "$deb" "$work/prefix"; done
  # The shared libraries those load, from this machine's packages, until closed.
  local round added lib real owner
  for round in 1 2 3 4; do
    added=0
    while read -r lib; do
      real=$(readlink -f "$lib")
      [ -e "$work/prefix$real" ] && continue
      owner=$(dpkg -S "$real" 2>/dev/null | head -n 1 | cut -d: -f1) || true
      [ -n "$owner" ] || owner=$(dpkg -S "$lib" 2>/dev/null | head -n 1 | cut -d: -f1) || true
      [ -n "$owner" ] || { log "no package owns $lib"; return 1; }
      (cd "$work/debs" && apt-get download "$owner" >/dev/null 2>&1) || { log "cannot download $owner"; return 1; }
      dpkg-deb -x "$(ls "$work"/debs/"${owner}"_*.deb | head -n 1)" "$work/prefix"
      added=1
    done < <(stage_needed_libs "$work/prefix")
    [ $added -eq 1 ] || break
  done
  # Left out: static archives (GoogleTest's and Benchmark's kept: their CMake
  # configs name them), Fortran, docs, manuals.
  find "$work/prefix" -name '*.a' ! -name 'libgtest*.a' ! -name 'libgmock*.a' ! -name 'libbenchmark*.a' -delete
  rm -rf "$work/prefix/usr/share/doc" "$work/prefix/usr/share/man" "$work/prefix/usr/share/lintian" \
    "$work/prefix"/usr/lib/x86_64-linux-gnu/fortran
  find "$work/prefix" \( -type f -o -type l \) -name 'lib*fortran*' -delete
  tar -cJf "$dir/debian-prefix.tar.xz" -C "$work/prefix" .

  {
    echo "lagremap device stage, made $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release && echo "$PRETTY_NAME")"
    echo "packages:"
    for deb in "$work"/debs/*.deb; do dpkg-deb -W --showformat='  ${Package} ${Version}\n' "$deb"; done
    echo "sizes (bytes):"
    (cd "$dir" && stat -c '  %s %n' kokkos-3.4.01-src.tar.gz debian-prefix.tar.xz)
    echo "  unpacked prefix: $(du -sb "$work/prefix" | cut -f1)"
  } > "$dir/MANIFEST.txt"
  rm -rf "$work"
  local total
  total=$(du -sb "$dir" | cut -f1)
  log "staged $dir: $((total / 1024 / 1024)) MiB (limit 60 MiB)"
  [ "$total" -le "$stage_limit_bytes" ] || { log "stage exceeds 60 MiB"; return 1; }
}

# Shared libraries that the ELF files of a prefix need and that it does not
# hold, outside the C/C++ runtimes (resolved on this machine).
stage_needed_libs() {
  local prefix=$1 f
  find "$prefix" -type f \( -name '*.so*' -o -perm -u+x \) | while read -r f; do
    head -c 4 "$f" 2>/dev/null | grep -q 'ELF' || continue
    LD_LIBRARY_PATH="$prefix/usr/lib/x86_64-linux-gnu:$prefix/usr/lib/x86_64-linux-gnu/openmpi/lib:$prefix/usr/lib/x86_64-linux-gnu/hdf5/openmpi" \
      ldd "$f" 2>/dev/null | awk '/=> \// {print $3}'
  done | sort -u | while read -r f; do
    case "$f" in "$prefix"/*) continue ;; esac
    basename "$f" | grep -Eq "$stage_system_libs" && continue
    echo "$f"
  done
}
