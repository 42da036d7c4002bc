#!/usr/bin/env bash
# A rank killed mid-frame (SIGKILL: no chance to clean up) makes the whole
# MPI job fail: mpirun names the rank and the signal, rank 0 (ended by mpirun)
# says the job was ended and nothing was written, the status is non-zero,
# and the output folder holds no file at all: no picture, no temporary.
source "$(dirname "$0")/lib.sh"
require_mpi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
mkdir out

# A frame of several seconds per rank (about 5 s of one core each on a quiet
# machine): the torus, 800x800, 128 samples a pixel, shadows.
mpirun --allow-run-as-root --oversubscribe -np 2 "$RAYFORM_BIN" render "$RAYFORM_SOURCE_DIR/scenes/assets/torus.obj" \
  -o out/frame.png --normals out/normals.png --size 800x800 --spp 128 --shadows --threads 1 -q >run.log 2>&1 &
job=$!
# Rank 1's process: a child of mpirun whose environment says so.
victim=
for _ in $(seq 100); do
  for p in $(pgrep -P "$job"); do
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1' && victim=$p
  done
  [ -n "$victim" ] && break
  sleep 0.1
done
[ -n "$victim" ] || { echo "FAIL: rank 1 not found among mpirun's children: $(cat run.log)"; kill "$job"; exit 1; }
sleep 1  # past loading (a few ms) into the render
kill -0 "$job" 2>/dev/null || { echo "FAIL: the job ended before rank 1 was killed: $(cat run.log)"; exit 1; }
kill -KILL "$victim"
wait "$job"; rc=$?
failures=0
fail() { echo "FAIL: $1"; failures=$((failures + 1)); }
[ $rc -ne 0 ] || fail "the job exited 0 with a rank killed"
grep -qiE 'rank 1 .*signal 9|signal 9 \(Killed\)' run.log || fail "no message naming the killed rank: $(cat run.log)"
grep -q 'rayform: rank 0 of 2 stopped: the MPI job was ended' run.log || fail "rank 0 did not say the job was ended: $(cat run.log)"
left=$(find out -mindepth 1 | wc -l)
[ "$left" -eq 0 ] || fail "files left in the output folder: $(ls -a out)"
[ $failures -eq 0 ] && echo "ok   rank 1 killed mid-frame: status $rc, no file left; stderr: $(grep -E 'rayform|signal' run.log | tr '\n' ' ')"
[ $failures -eq 0 ]
