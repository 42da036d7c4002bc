#!/usr/bin/env bash
# Batch renders (cli/render_batch.h): `rayform render a b c ... -o
# 'out/{stem}.png'` renders every file in one process, and under mpirun
# spreads them over ranks (2 and 3). Good files give the pictures a render of
# each alone gives, byte for byte; each bad file (malformed, missing, unknown
# format) gives one line naming it and no output; the status is 1 when any
# failed, 0 when none did. A turntable (--frames N) writes N pictures, frame k
# being the --orbit camera turned by k * 360 / N degrees. Templates that
# would write one file twice are usage errors (status 2). The one-process
# part needs no MPI and no third-party data. Under mpirun, info and convert
# run on rank 0 alone.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

assets=$RAYFORM_SOURCE_DIR/scenes/assets
mkdir in
cp "$assets/torus.obj" "$assets/box.obj" "$assets/features.glb" in/
write_sphere_scene in/sphere.txt
printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' >in/broken.obj     # a face naming a vertex the file lacks
printf '{"asset": {"version": "2.0"}, "nodes": [' >in/cut.gltf  # JSON cut short
printf 'hello\n' >in/notes.xyz                            # no scene format
good=(in/torus.obj in/box.obj in/features.glb in/sphere.txt)
bad=(in/broken.obj in/cut.gltf in/notes.xyz in/missing.obj)
common=(--size 40x30)

# Each good file alone: the reference pictures.
mkdir ref
for f in "${good[@]}"; do
  stem=$(basename "${f%.*}")
  "$RAYFORM_BIN" render "$f" -o "ref/$stem.png" --normals "ref/${stem}_n.png" "${common[@]}" -q ||
    fail reference "$f did not render"
done

# check NAME RUNNER...: the batch with RUNNER (empty: one process).
check() {
  local name=$1 before=$failures; shift
  rm -rf out; mkdir out
  "$@" render "${good[@]:0:2}" "${bad[@]}" "${good[@]:2}" -o 'out/{stem}.png' --normals 'out/{stem}_n.png' \
    "${common[@]}" -q >"$name.log" 2>&1
  local rc=$?
  [ $rc -eq 1 ] || fail "$name" "exit $rc, expected 1: $(cat "$name.log")"
  for f in "${good[@]}"; do
    local stem; stem=$(basename "${f%.*}")
    for out in "$stem.png" "${stem}_n.png"; do
      cmp -s "ref/$out" "out/$out" || fail "$name" "out/$out is missing or differs from rendering $f alone"
    done
  done
  for f in "${bad[@]}"; do
    local n; n=$(grep -c "^rayform: error: .*$(basename "$f")" "$name.log")
    [ "$n" -eq 1 ] || fail "$name" "expected one error line naming $f, got $n: $(cat "$name.log")"
  done
  grep -q "^rayform: 4 of 8 renders failed" "$name.log" || fail "$name" "no summary line: $(cat "$name.log")"
  [ "$(find out -type f | wc -l)" -eq 8 ] || fail "$name" "expected the 8 good outputs only: $(ls out)"
  [ $failures -eq $before ] && echo "ok   [$name] 4 good files rendered, 4 bad ones reported, status 1"
}
check one-process "$RAYFORM_BIN"
"$RAYFORM_BIN" render "${good[@]}" -o 'out/{stem}.png' "${common[@]}" -q || fail all-good "exit $? for good files only"

# Turntable: --frames 4 from --orbit 30,20 -> azimuths 30, 120, 210, 300.
rm -rf spin; mkdir spin
"$RAYFORM_BIN" render in/features.glb --frames 4 --orbit 30,20 -o 'spin/f{frame}.png' "${common[@]}" -q ||
  fail turntable "exit $?"
"$RAYFORM_BIN" render in/features.glb --orbit 210,20 -o spin/alone.png "${common[@]}" -q
[ "$(find spin -name 'f*.png' | wc -l)" -eq 4 ] || fail turntable "expected f0000..f0003.png: $(ls spin)"
cmp -s spin/alone.png spin/f0002.png || fail turntable "frame 2 is not the picture at azimuth 210"
cmp -s spin/f0000.png spin/f0001.png && fail turntable "frames 0 and 1 are the same picture"
[ $failures -eq 0 ] && echo "ok   [turntable] 4 frames, frame 2 = --orbit 210,20"

# Usage errors, nothing written: several inputs without {stem}, --frames without {frame},
# two inputs with one stem, an unknown placeholder.
rm -rf out; mkdir out
usage() {
  local what=$1; shift
  "$RAYFORM_BIN" render "$@" >usage.log 2>&1; local rc=$?
  [ $rc -eq 2 ] || fail usage "$what: exit $rc, expected 2: $(cat usage.log)"
  [ "$(find out -type f | wc -l)" -eq 0 ] || fail usage "$what: wrote $(ls out)"
}
usage "no {stem}" in/torus.obj in/box.obj -o out/x.png
usage "no {frame}" in/torus.obj --frames 3 -o 'out/{stem}.png'
usage "one stem twice" in/torus.obj "$assets/torus.obj" -o 'out/{stem}.png'
usage "unknown placeholder" in/torus.obj in/box.obj -o 'out/{name}.png'
[ $failures -eq 0 ] && echo "ok   [usage] 4 template mistakes refused with status 2"

# The same batch over 2 and 3 ranks.
if (require_mpi >/dev/null); then
  require_mpi
  check mpi-2 mpirun --allow-run-as-root --oversubscribe -np 2 "$RAYFORM_BIN"
  check mpi-3 mpirun --allow-run-as-root --oversubscribe -np 3 "$RAYFORM_BIN"
  # --stats: one line per rank, the renders adding up to 8.
  rm -rf out; mkdir out
  mpi_run 2 render "${good[@]}" "${bad[@]}" -o 'out/{stem}.png' "${common[@]}" -q --stats >stats.log 2>&1
  sum=$(sed -nE 's/^stats: rank [01] of 2: ([0-9]+) renders.*/\1/p' stats.log | awk '{s += $1} END {print s}')
  [ "$sum" = 8 ] || fail mpi-stats "the ranks' renders add up to '$sum', not 8: $(cat stats.log)"
  [ $failures -eq 0 ] && echo "ok   [mpi-stats] 2 ranks report 8 renders in all"
  # A turntable over ranks: the same frames.
  rm -rf spin3; mkdir spin3
  mpi_run 3 render in/features.glb --frames 4 --orbit 30,20 -o 'spin3/f{frame}.png' "${common[@]}" -q ||
    fail mpi-turntable "exit $?"
  for k in 0 1 2 3; do cmp -s "spin/f000$k.png" "spin3/f000$k.png" || fail mpi-turntable "frame $k differs"; done
  [ $failures -eq 0 ] && echo "ok   [mpi-turntable] 4 frames over 3 ranks, identical"
  # info and convert under mpirun: rank 0 alone reports and writes.
  n=$(mpi_run 2 info in/box.obj 2>/dev/null | grep -c '^triangles:')
  [ "$n" = 1 ] || fail mpi-info "expected one report from 2 ranks, got $n"
  mpi_run 2 convert in/box.obj box.glb -q >convert.log 2>&1 || fail mpi-convert "exit $?: $(cat convert.log)"
  [ -s box.glb ] || fail mpi-convert "box.glb not written"
  [ $failures -eq 0 ] && echo "ok   [mpi-info-convert] one report, one file"
else
  echo "note: MPI parts skipped ($(require_mpi))"
fi

echo "$failures failure(s)"
[ $failures -eq 0 ]
