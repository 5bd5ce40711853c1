#!/usr/bin/env bash
# Fault injection (issue 30): what a run promises when it is abused, on
# sedov at 15^3 cells (a checkpoint every step) and 32^3 (the full disk).
#  1. kill -9, ten times, each soon after a checkpoint write has begun: the
#     last checkpoint always restarts (a half-written one is never taken),
#     and the run, restarted after each kill, ends with the bits of an
#     uninterrupted run (history.csv, the radial profile, the final fields).
#  2. a mantissa bit flipped in a checkpoint (cells/E_c, nodes/x_n): exit
#     code 2 and one line naming the file and the dataset.
#  3. a full disk (10 MB tmpfs; needs root, skipped otherwise), on 1 and 2
#     ranks: exit code 3, one line from lagremap and no HDF5 dump, nothing
#     half-written left, the previous checkpoint restarts, history.csv in
#     step with the last step taken.
#  4. one rank of a 2-rank job killed: the job ends, non-zero, within 60 s.
#   tests/fault_injection.sh LAGREMAP_EXE SCRATCH_DIR [SEED]
set -euo pipefail
exe=$1
out=$2
RANDOM=${3:-$$}
rm -rf "$out"
mkdir -p "$out"
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
python=/usr/bin/python3
start=$SECONDS

fail() {
  echo "fault_injection: $*" >&2
  exit 1
}
# Seconds, for sleep: a random number of milliseconds in [$1, $1 + $2).
random_seconds() {
  local ms=$(($1 + RANDOM % $2))
  printf '%d.%03d' $((ms / 1000)) $((ms % 1000))
}
# Checkpoint $1 of a run of the problem options $2... restarts: a restart
# stopped by a step limit at once (a checkpoint is at step 1 or later) read
# and accepted it.
check_restarts() {
  local checkpoint=$1 log=$out/restart_check.log
  shift
  "$exe" "$@" --quiet --output "$out/restart_check" --set numerics.max_steps=1 \
    --restart "$checkpoint" > "$log" 2>&1 || true
  grep -q "numerics.max_steps reached" "$log" ||
    fail "checkpoint $checkpoint does not restart: $(cat "$log")"
}

# --- 1. kill -9 during checkpoints
sedov=(--problem sedov --scale 0.5 --checkpoint-every 1 --quiet)
"$exe" "${sedov[@]}" --output "$out/whole" > "$out/whole.log" 2>&1 ||
  fail "the uninterrupted run failed: $(cat "$out/whole.log")"
run=$out/killed
kills=0 mid_write=0 attempts=0
while [ $kills -lt 10 ]; do
  attempts=$((attempts + 1))
  [ $attempts -le 40 ] || fail "$kills kills in 40 attempts"
  restart=()
  [ -f "$run/checkpoint.h5" ] && restart=(--restart "$run/checkpoint.h5")
  "$exe" "${sedov[@]}" --output "$run" "${restart[@]}" > "$run.log" 2>&1 &
  pid=$!
  # A random moment after the start-up, then the next checkpoint write
  # (its .tmp appears) or at most a second more.
  sleep "$(random_seconds 300 700)"
  for _ in $(seq 200); do
    [ -e "$run/checkpoint.h5.tmp" ] && break
    kill -0 $pid 2> /dev/null || break
    sleep 0.005
  done
  kill -9 $pid 2> /dev/null || true
  status=0
  { wait $pid; } 2> /dev/null || status=$?  # (not bash's "Killed" line)
  if [ $status -ne 137 ]; then  # it ended by itself first: it must have finished
    [ $status -eq 0 ] || fail "a restarted run failed (exit $status): $(cat "$run.log")"
    break
  fi
  kills=$((kills + 1))
  [ -e "$run/checkpoint.h5.tmp" ] && mid_write=$((mid_write + 1))
  [ -f "$run/checkpoint.h5" ] && check_restarts "$run/checkpoint.h5" "${sedov[@]}"
done
if [ $kills -lt 10 ]; then
  fail "the run finished after $kills kills: make it longer or the waits shorter"
fi
"$exe" "${sedov[@]}" --output "$run" --restart "$run/checkpoint.h5" > "$run.log" 2>&1 ||
  fail "the last restart failed: $(cat "$run.log")"
for file in history.csv radial.csv; do
  cmp -s "$out/whole/$file" "$run/$file" || fail "$file differs from the uninterrupted run's"
done
if $python -c "import h5py, numpy" 2> /dev/null; then
  $python - "$out/whole" "$run" <<'PY' || fail "the final fields differ from the whole run's"
import glob, sys
import h5py, numpy
def last(folder):
    return h5py.File(sorted(glob.glob(folder + "/fields_*.h5"))[-1], "r")
whole, killed = last(sys.argv[1]), last(sys.argv[2])
names = []
whole.visit(lambda name: names.append(name) if isinstance(whole[name], h5py.Dataset) else None)
for name in names:
    if not numpy.array_equal(whole[name][()], killed[name][()]):
        sys.exit("fault_injection: %s differs" % name)
PY
  fields="and final fields"
else
  fields="(final fields not compared: no h5py for $python)"
fi
echo "kill -9: 10 kills ($mid_write mid-write), each last checkpoint restarted;" \
  "history, radial profile $fields identical to the uninterrupted run"

# --- 2. a flipped bit
if $python -c "import h5py" 2> /dev/null; then
  for dataset in cells/E_c nodes/x_n; do
    copy=$out/flipped_${dataset%%/*}.h5
    cp "$run/checkpoint.h5" "$copy"
    $python - "$copy" "$dataset" <<'PY'
import sys
import h5py
path, name = sys.argv[1:3]
with h5py.File(path, "r") as f:
    offset = f[name].id.get_offset() + 8 * 100 + 3  # value 100, mantissa bit 26
with open(path, "r+b") as f:
    f.seek(offset)
    byte = f.read(1)[0]
    f.seek(offset)
    f.write(bytes([byte ^ 4]))
PY
    status=0
    "$exe" "${sedov[@]}" --output "$out/flipped" --restart "$copy" > "$out/flipped.log" 2>&1 ||
      status=$?
    [ $status -eq 2 ] || fail "a flipped bit in $dataset: exit $status, not 2"
    [ "$(wc -l < "$out/flipped.log")" -eq 1 ] || fail "a flipped bit: $(cat "$out/flipped.log")"
    grep -q "'$copy'.*$dataset" "$out/flipped.log" ||
      fail "a flipped bit: the message names neither file nor dataset: $(cat "$out/flipped.log")"
  done
  echo "flipped bit: exit code 2, one line naming the file and the dataset (cells/E_c, nodes/x_n)"
else
  echo "flipped bit: skipped (no h5py for $python to find a dataset's bytes)"
fi

# --- 3. a full disk
disk=$out/disk
mkdir -p "$disk"
if [ "$(id -u)" -eq 0 ] && mount -t tmpfs -o size=10m tmpfs "$disk" 2> /dev/null; then
  trap 'umount "$disk" 2> /dev/null || true' EXIT
  for ranks in 1 2; do
    rm -rf "${disk:?}"/*
    status=0
    timeout 120 mpiexec -np $ranks --bind-to none "$exe" --problem sedov --quiet \
      --checkpoint-every 2 --set numerics.max_steps=6 --output "$disk/run" \
      > "$out/disk.log" 2>&1 || status=$?
    [ $status -eq 3 ] || fail "full disk, $ranks ranks: exit $status, not 3: $(cat "$out/disk.log")"
    if [ "$(grep -c '^lagremap' "$out/disk.log")" -ne 1 ] ||
      grep -qE "HDF5-DIAG|infinite loop|Segmentation" "$out/disk.log"; then
      fail "full disk, $ranks ranks: $(cat "$out/disk.log")"
    fi
    for left in "$disk"/run/*.tmp "$disk"/run/*.room; do
      [ ! -e "$left" ] || fail "full disk, $ranks ranks: $left left"
    done
    # the header, the initial state and steps 1 to 4, whole lines
    history=$disk/run/history.csv
    if [ -n "$(tail -c 1 "$history")" ] || [ "$(wc -l < "$history")" -ne 6 ] ||
      [ "$(tail -n 1 "$history" | cut -d, -f1)" != 4 ]; then
      fail "full disk, $ranks ranks: history.csv does not end with step 4: $(tail -n 2 "$history")"
    fi
    check_restarts "$disk/run/checkpoint.h5" --problem sedov
  done
  umount "$disk"
  trap - EXIT
  echo "full disk: exit code 3, one line, nothing half-written, the step-2 checkpoint restarts," \
    "history.csv to step 4 (1 and 2 ranks)"
else
  echo "full disk: skipped (mounting a small tmpfs needs root)"
fi

# --- 4. one rank of two killed (sedov at 32^3 runs for minutes: alive at 2 s)
mpiexec -np 2 --bind-to none "$exe" --problem sedov --quiet --output "$out/rank" \
  > "$out/rank.log" 2>&1 &
launcher=$!
sleep 2
rank=$(pgrep -P $launcher | tail -n 1 || true)
[ -n "$rank" ] || fail "no rank of the 2-rank job found to kill"
kill -9 "$rank"
for _ in $(seq 600); do
  kill -0 $launcher 2> /dev/null || break
  sleep 0.1
done
if kill -0 $launcher 2> /dev/null; then
  kill -9 $launcher
  fail "the 2-rank job still runs 60 s after one rank was killed"
fi
status=0
wait $launcher || status=$?
[ $status -ne 0 ] || fail "the 2-rank job with a killed rank exited 0"
echo "one rank killed: the job ended (exit $status)"
echo "fault_injection: all passed in $((SECONDS - start)) s"
