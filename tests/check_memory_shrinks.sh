#!/usr/bin/env bash
# The set-up's memory per rank shrinks with the rank count (issue: no rank
# builds an array over the whole mesh). `sedov` at 48^3 cells (110,592), one
# step, on 1 and on 4 ranks: the largest rank's peak resident memory at the
# end of set-up (summary.json memory.setup_peak_bytes) on 4 ranks must be
# below half the single rank's. Each of the 4 parts holds about 29% of the
# cells (a quarter plus its ghost layers); MPI, Kokkos and the executable
# add a fixed 25-30 MB. Measured: 0.39 with the distributed set-up; 0.54
# when every rank generated the whole mesh and its initial cells first.
#   tests/check_memory_shrinks.sh LAGREMAP_EXE SCRATCH_DIR
set -euo pipefail
exe=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
for ranks in 1 4; do
  dir=$out/ranks_$ranks
  status=0
  mpiexec -np "$ranks" --bind-to none "$exe" --problem sedov --set mesh.nx=48 --set mesh.ny=48 \
    --set mesh.nz=48 --set numerics.max_steps=1 --quiet --output "$dir" > "$dir.log" 2>&1 ||
    status=$?
  # the step limit ends the run on purpose (exit code 3, "max_steps reached")
  if ! grep -q "max_steps reached" "$dir.log" || [ ! -f "$dir/summary.json" ]; then
    echo "check_memory_shrinks: $ranks ranks failed (exit $status):" >&2
    cat "$dir.log" >&2
    exit 1
  fi
done
/usr/bin/python3 - "$out/ranks_1/summary.json" "$out/ranks_4/summary.json" <<'PY'
import json, sys
one, four = (json.load(open(path))["memory"] for path in sys.argv[1:3])
single = one["setup_peak_bytes"]["max"]
largest = four["setup_peak_bytes"]["max"]
ratio = largest / single
print("set-up peak: 1 rank %.1f MB, 4 ranks (largest) %.1f MB, ratio %.2f"
      % (single / 1e6, largest / 1e6, ratio))
if not (single > 0 and ratio < 0.5):
    sys.exit("check_memory_shrinks: the largest of 4 ranks peaks at %.2f of the single rank "
             "at the end of set-up (must be below 0.5)" % ratio)
PY
