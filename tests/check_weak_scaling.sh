#!/usr/bin/env bash
# perf/weak_scaling.sh and perf/scaling_model.py on a tiny case: 6^3 cells
# per rank on 1, 2 and 8 ranks, 3 steps. Checks what does not depend on the
# machine: the meshes and process grids, the halo's messages per step (one
# per neighbour rank and exchange, four exchanges per lagrange step: 2 ranks
# x 1 neighbour x 4, 8 ranks x 7 x 4), its bytes growing with the cut faces
# (2x2x2: 12 cut faces against 1 at 2 ranks), and that the model prints its
# three rank counts with efficiencies in (0, 1].
#   tests/check_weak_scaling.sh BUILD_DIR SCRATCH_DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$1
out=$2
rm -rf "$out"
LAGREMAP_BUILD_DIR=$build WEAK_CELLS_PER_EDGE=6 WEAK_RANKS="1 2 8" WEAK_STEPS=3 \
  "$here/perf/weak_scaling.sh" "$out" > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
/usr/bin/python3 "$here/perf/scaling_model.py" "$out/results.csv" > "$out/model.md"
/usr/bin/python3 - "$out/results.csv" "$out/model.md" <<'PY'
import csv, sys
rows = {int(r["ranks"]): r for r in csv.DictReader(open(sys.argv[1]))}
def fail(why):
    sys.exit("check_weak_scaling: " + why)
if sorted(rows) != [1, 2, 8]:
    fail("rank counts %s" % sorted(rows))
expected = {1: ("1x1x1", 216, 0), 2: ("2x1x1", 432, 8), 8: ("2x2x2", 1728, 224)}
for ranks, (grid, cells, messages) in expected.items():
    r = rows[ranks]
    if r["grid"] != grid or int(r["cells"]) != cells or int(r["cells_per_rank"]) != 216:
        fail("%d ranks: grid %s, %s cells" % (ranks, r["grid"], r["cells"]))
    if float(r["halo_messages_per_step"]) != messages:
        fail("%d ranks: %s messages per step, expected %d" % (ranks, r["halo_messages_per_step"], messages))
    if not float(r["peak_max"]) > 0 or not float(r["setup_total"]) >= 0:
        fail("%d ranks: no memory or set-up report" % ranks)
bytes2, bytes8 = float(rows[2]["halo_bytes_per_step"]), float(rows[8]["halo_bytes_per_step"])
if not (bytes2 > 0 and 6 * bytes2 < bytes8 < 20 * bytes2):
    fail("halo bytes per step %g (2 ranks) and %g (8 ranks)" % (bytes2, bytes8))
lines = [l for l in open(sys.argv[2]) if l.startswith("| ") and l[2].isdigit()]
if [l.split("|")[1].strip() for l in lines] != ["64", "512", "4096"]:
    fail("model rows %s" % lines)
for l in lines:
    cells = [c.strip() for c in l.split("|")]
    weak, strong = float(cells[4]), float(cells[7])
    if not (0 < weak <= 1 and 0 < strong <= 1.0000001):
        fail("model efficiencies %s" % l)
print("weak scaling script and model: ok")
PY
