#!/usr/bin/env bash
# Fault injection (issue 30): what a run promises when it is abused, on
# sedov at 23^3 cells (a checkpoint every step) and 30^3 (the full disk).
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
#  5. hostile options, decks, checkpoints, outputs and signals: Kokkos'
#     number flags and thread counts, a length out of range, numbers as
#     strings or in hex, a long path, a directory as a checkpoint, a
#     checkpoint's format attribute edited, a restart under other keys or
#     below the time-step floor: exit code 2 and one line; a directory where
#     a result file goes, an output filesystem out of space or inodes (1 and
#     2 ranks): exit 3 and one line, never exit 0 without summary.json;
#     SIGTERM, SIGINT, SIGUSR1: exit 4 with a checkpoint and summary.json
#     "stopped", a second signal ends the run at once.
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
sedov=(--problem sedov --scale 0.75 --checkpoint-every 1 --quiet)
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
# --- 5. hostile input, outputs and signals
# expect CODE TEXT ARGS...: lagremap ARGS exits CODE with one line on stderr
# holding TEXT.
expect() {
  local code=$1 text=$2 status=0
  shift 2
  "$exe" "$@" > "$out/case.out" 2> "$out/case.err" || status=$?
  local args="$*"
  [ ${#args} -le 300 ] || args="${args:0:150}...${args: -150}"
  [ $status -eq "$code" ] || fail "$args: exit $status, not $code: $(head -c 600 "$out/case.err")"
  [ "$(wc -l < "$out/case.err")" -eq 1 ] || fail "$args: not one line: $(head -c 600 "$out/case.err")"
  grep -qF -- "$text" "$out/case.err" || fail "$args: no '$text' in: $(head -c 600 "$out/case.err")"
}
sod=(--problem sod --scale 0.25 --quiet --output "$out/sod")
expect 2 "--kokkos-threads=-3: must be at least 1" "${sod[@]}" --kokkos-threads=-3
expect 2 "--kokkos-threads=abc: expects a whole number" "${sod[@]}" --kokkos-threads=abc
expect 2 "expects --kokkos-threads=N" "${sod[@]}" --kokkos-threads
expect 2 "--kokkos-num-threads=-1" "${sod[@]}" --kokkos-num-threads=-1
expect 2 "--kokkos-device-id=-5" "${sod[@]}" --kokkos-device-id=-5
expect 2 "--kokkos-num-devices=-1" "${sod[@]}" --kokkos-num-devices=-1
expect 2 "at most 512 threads" "${sod[@]}" --kokkos-threads=5000
OMP_NUM_THREADS=100000 expect 2 "OMP_NUM_THREADS=100000: at most 512" "${sod[@]}"
expect 2 "rod.length = 1e+300 m is out of range" --problem rod --set rod.length=1e300
expect 2 "bad value '0x1p1' for key 'left.rho'" "${sod[@]}" --set left.rho=0x1p1
printf 'problem = "sod"\n[left]\nrho = "2.0"\n' > "$out/string.toml"
expect 2 "key 'left.rho' is a number" --input "$out/string.toml" --quiet --output "$out/sod"
printf 'problem = "sod"\n[mesh]\nnx = 0x40\n' > "$out/hex.toml"
expect 2 "write the number in decimal" --input "$out/hex.toml" --quiet --output "$out/sod"
long=$out/$(printf 'a%.0s' $(seq 5000))
expect 2 "File name too long" "${sod[@]}" --restart "$long"
[ "$(wc -c < "$out/case.err")" -lt 300 ] || fail "a long path: a $(wc -c < "$out/case.err")-byte line"
expect 2 "is a directory, not a checkpoint file" "${sod[@]}" --restart "$out"
# A checkpoint: sod stopped at step 20 (exit 3 by the step limit)
"$exe" "${sod[@]}" --set numerics.max_steps=20 > /dev/null 2>&1 || true
checkpoint=$out/sod/checkpoint.h5
[ -f "$checkpoint" ] || fail "the stopped sod left no checkpoint"
expect 2 "numerics.dt_min_fraction x t_end" "${sod[@]}" --restart "$checkpoint" \
  --set numerics.dt_min_fraction=0.5
expect 2 "was written with left.rho=1; this run has left.rho=2" "${sod[@]}" \
  --restart "$checkpoint" --set left.rho=2
jc=(--problem rod --scale 0.25 --quiet --set metal.jc_B=3e8 --set metal.jc_n=0.3)
"$exe" "${jc[@]}" --set metal.hardening=johnson_cook --output "$out/jc" \
  --set numerics.max_steps=5 > /dev/null 2>&1 || true
expect 2 "this run has metal.hardening=perfect" "${jc[@]}" --set metal.hardening=perfect \
  --output "$out/jc" --restart "$out/jc/checkpoint.h5"
if $python -c "import h5py" 2> /dev/null; then
  cp "$checkpoint" "$out/format_1.h5"
  $python - "$out/format_1.h5" <<'PY'
import sys
import h5py
import numpy
with h5py.File(sys.argv[1], "r+") as f:  # (fixed-length text, as written)
    f.attrs["format"] = numpy.bytes_(b"lagremap checkpoint 1")
PY
  expect 2 "corrupted" "${sod[@]}" --restart "$out/format_1.h5"
fi
# A directory where a result file goes
for file in summary.json sod_profile.csv; do
  rm -rf "$out/sod" && mkdir -p "$out/sod/$file"
  expect 3 "$out/sod/$file" "${sod[@]}"
done
rm -rf "$out/sod"
# An output filesystem out of space or inodes, at each of the run's files
starved=$out/starved
mkdir -p "$starved"
if [ "$(id -u)" -eq 0 ] && mount -t tmpfs -o size=1m tmpfs "$starved" 2> /dev/null; then
  umount "$starved"
  trap 'umount "$starved" 2> /dev/null || true' EXIT
  for ranks in 1 2; do
    for limit in size=72k nr_inodes=4 nr_inodes=5 nr_inodes=6 nr_inodes=7 nr_inodes=8 \
      nr_inodes=9 nr_inodes=10; do
      mount -t tmpfs -o "size=8m,$limit" tmpfs "$starved"
      status=0
      timeout 120 mpiexec -np $ranks --bind-to none "$exe" --problem sod --scale 0.5 --quiet \
        --output "$starved/run" > "$out/starved.log" 2>&1 || status=$?
      lines=$(grep -c '^lagremap' "$out/starved.log" || true)
      case $status in
        0) [ -f "$starved/run/summary.json" ] ||
          fail "output out of $limit, $ranks ranks: exit 0 and no summary.json" ;;
        3) [ "$lines" -eq 1 ] ||
          fail "output out of $limit, $ranks ranks: $lines lines: $(cat "$out/starved.log")" ;;
        *) fail "output out of $limit, $ranks ranks: exit $status: $(cat "$out/starved.log")" ;;
      esac
      umount "$starved"
    done
  done
  trap - EXIT
  echo "starved output: exit 3 and one line, or 0 with summary.json (space, inodes; 1, 2 ranks)"
else
  echo "starved output: skipped (mounting a small tmpfs needs root)"
fi
# Signals: the run stops at the end of its step with its checkpoint
for signal in TERM INT USR1; do
  rm -rf "$out/signal"
  "$exe" --problem sedov --quiet --output "$out/signal" > /dev/null 2> "$out/signal.err" &
  pid=$!
  sleep 2
  kill -$signal $pid
  status=0
  wait $pid || status=$?
  [ $status -eq 4 ] || fail "SIG$signal: exit $status, not 4: $(cat "$out/signal.err")"
  [ "$(wc -l < "$out/signal.err")" -eq 1 ] || fail "SIG$signal: $(cat "$out/signal.err")"
  grep -q '"status": "stopped"' "$out/signal/summary.json" ||
    fail "SIG$signal: summary.json not \"stopped\""
  check_restarts "$out/signal/checkpoint.h5" --problem sedov
done
# A second signal ends it at once (killed by it: 128 + 15)
rm -rf "$out/signal"
"$exe" --problem sedov --scale 2 --quiet --output "$out/signal" > /dev/null 2>&1 &
pid=$!
sleep 2
kill -TERM $pid
sleep 0.5 # (two pending at once would be one)
kill -TERM $pid
status=0
wait $pid || status=$?
[ $status -eq 143 ] || fail "two SIGTERMs: exit $status, not 143"
echo "hostile input, outputs, signals: one line and the documented exit code each"
echo "fault_injection: all passed in $((SECONDS - start)) s"
