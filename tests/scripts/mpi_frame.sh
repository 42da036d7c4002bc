#!/usr/bin/env bash
# One frame over MPI ranks (docs/distributed.md): `mpirun -np N rayform render
# ...` writes exactly the files, byte for byte, that one process writes with
# the same options: colour and every AOV (depth, normals, albedo, coverage as
# the colour's alpha), for 2 and 3 ranks, for a course scene (the course's
# own command line too), an asset, a glass scene with --spp 16 --shadows
# --bounces 3, and an OBJ large enough for the ranks to share its parse and
# the smooth normals and BVH builds of its large meshes (ObjReadOptions::share,
# share_min_faces, BvhBuildOptions::share_min_triangles: 32768); --stats shows
# each rank's share of the tiles, which add up to the frame's.
source "$(dirname "$0")/lib.sh"
require_mpi
require_shared
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

course=$RAYFORM_SHARED/course
# An OBJ text of more than 1 MiB, whose parse the ranks share (ObjReadOptions::share):
# a wavy grid of triangles and quads without normals in three groups, of 43800, 43800 and
# 8322 triangles once split: the first two over the thresholds at which the ranks share a
# mesh's smooth normals (ObjReadOptions::share_min_faces) and its BVH build
# (build_mesh_accel with a WorkShare), the third under them (each rank makes it whole).
awk -v n=220 'BEGIN {
  for (y = 0; y < n; y++) for (x = 0; x < n; x++)
    printf "v %.5f %.5f %.5f\n", x / n - 0.5, y / n - 0.5, 0.05 * sin(x * 0.3) * cos(y * 0.2)
  for (y = 0; y + 1 < n; y++) {
    if (y % 100 == 0) print "g band" y
    for (x = 0; x + 1 < n; x++) {
      a = y * n + x + 1
      if ((x + y) % 3 == 0) printf "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n
      else printf "f %d %d %d\nf %d %d %d\n", a, a + 1, a + n + 1, a, a + n + 1, a + n
    }
  }
}' >grid.obj
[ "$(wc -c <grid.obj)" -gt 1048576 ] || fail obj-shared "grid.obj is too small to take the shared parse"
# name | arguments before the outputs | outputs (each NAME, replaced by one/NAME and n/NAME)
cases=(
  "course|render $course/2012/scene07_shine.txt --size 97x61 -q|-o @c.png --depth 8:18:@d.png --normals @n.png"
  "asset|render $RAYFORM_SOURCE_DIR/scenes/assets/features.glb --size 80x67 --orbit 30,20 -q|-o @c.png --transparent --normals @n.png --albedo @a.png --depth 1:9:@d.png"
  "asset-float|render $RAYFORM_SOURCE_DIR/scenes/assets/features.glb --size 53x40 -q|-o @c.exr --transparent --albedo @a.exr"
  "glass|render $course/2012-a5/scene13_diamond.txt --size 64x48 --spp 16 --shadows --bounces 3 -q|-o @c.png --albedo @a.png --normals @n.png"
  "course-line|-input $course/2019/scene06_bunny_1k.txt -size 50 50 -dialect 2019 -shadows -quiet|-output @c.png -depth 8 12 @d.png -normals @n.png"
  # Two-pass sampling: the first pass covers the whole image on every rank, the second is shared.
  "grid-filter|-input $course/2012-a5/scene10_sphere.txt -size 61 47 -jitter -filter -shadows -quiet|-output @c.png"
  "adaptive|render $course/2012-a5/scene10_sphere.txt --size 61x47 --target-error 0.01 --shadows -q|-o @c.png --albedo @a.png"
  # A large OBJ: the ranks share its parse and its BVH build, and the frame is still the one-process frame.
  "obj-shared|render grid.obj --size 72x54 --orbit 20,50 --spp 4 -q|-o @c.png --normals @n.png --albedo @a.png --depth 1:6:@d.png"
)
for c in "${cases[@]}"; do
  IFS='|' read -r name args outs <<<"$c"
  before=$failures
  mkdir -p "one/$name"
  # shellcheck disable=SC2086  # word splitting intended
  "$RAYFORM_BIN" $args ${outs//@/one/$name/} 2>"one/$name.err" || { fail "$name" "one process: $(cat "one/$name.err")"; continue; }
  for np in 2 3; do
    mkdir -p "n$np/$name"
    # shellcheck disable=SC2086
    mpi_run "$np" $args ${outs//@/n$np/$name/} >"n$np/$name.log" 2>&1 ||
      { fail "$name" "$np ranks: exit $?: $(cat "n$np/$name.log")"; continue; }
    for f in "one/$name"/*; do
      g=n$np/$name/$(basename "$f")
      if [ ! -f "$g" ]; then fail "$name" "$np ranks wrote no $(basename "$f")"
      elif [ "${f##*.}" = exr ]; then
        # OpenEXR files hold the time they were written: compare the pixels, exactly.
        idiff -fail 0 -warn 0 "$f" "$g" >/dev/null || fail "$name" "$np ranks: $(basename "$f")'s pixels differ"
      elif ! cmp -s "$f" "$g"; then fail "$name" "$np ranks: $(basename "$f") differs from the one-process file"
      fi
    done
    extra=$(find "n$np/$name" -type f | wc -l) want=$(find "one/$name" -type f | wc -l)
    [ "$extra" -eq "$want" ] || fail "$name" "$np ranks left $extra files, one process $want"
  done
  [ "$failures" -eq "$before" ] && echo "ok   [$name] identical for 2 and 3 ranks ($(find "one/$name" -type f | wc -l) files)"
done

# --stats: one line per rank, rank 0 first, tiles adding up to the frame's
# (160x120 in tiles of 16: 10 x 8 = 80), and ranks other than 0 rendered some
# of them (so the pictures above went through the gather).
mpi_run 3 render "$course/2012-a5/scene13_diamond.txt" --size 160x120 --spp 16 --shadows --bounces 3 -o stats.png \
  --stats 2>stats.err >/dev/null || fail stats "exit $?: $(cat stats.err)"
ranks=$(grep -c '^stats: rank [0-2] of 3: [0-9]* of 80 tiles' stats.err)
[ "$ranks" -eq 3 ] || fail stats "expected 3 per-rank lines, got: $(cat stats.err)"
sum=$(sed -nE 's/^stats: rank [0-9]+ of 3: ([0-9]+) of 80 tiles.*/\1/p' stats.err | awk '{s += $1} END {print s}')
others=$(sed -nE 's/^stats: rank [12] of 3: ([0-9]+) of 80 tiles.*/\1/p' stats.err | awk '{s += $1} END {print s}')
[ "$sum" = 80 ] || fail stats "the ranks' tiles add up to $sum, not 80: $(cat stats.err)"
[ "${others:-0}" -gt 0 ] || fail stats "ranks 1 and 2 rendered no tile: $(cat stats.err)"
grep -q '^stats: load' stats.err || fail stats "no whole-job stats line from rank 0: $(cat stats.err)"
[ "$(grep -c '^stats: load' stats.err)" -eq 1 ] || fail stats "the whole-job line printed more than once"
[ $failures -eq 0 ] && echo "ok   [stats] 3 ranks report $sum tiles in all, $others by ranks 1 and 2"

# Every rank fails to read a bad scene: one message (rank 0's), status 1, no file.
printf 'v 0 0 0\nf 1 2 3\n' >bad.obj
mpi_run 2 render bad.obj -o bad.png >bad.log 2>&1; rc=$?
[ $rc -eq 1 ] || fail bad-scene "exit $rc, expected 1: $(cat bad.log)"
[ "$(grep -c 'bad.obj' bad.log)" -eq 1 ] || fail bad-scene "expected one line naming bad.obj: $(cat bad.log)"
[ -e bad.png ] && fail bad-scene "an output was written"
[ $failures -eq 0 ] && echo "ok   [bad-scene] one message, status 1, no output"

# A rank that cannot open the file the others read (a path missing on its
# node; here each rank works in its own folder, rank 1's without the OBJ), or
# reads another copy, stops the job before any shared work, rank 0 naming it:
# the others must not wait for it in the shared parse's exchange.
mkdir -p r0 r1 && cp grid.obj r0/
per_rank_folder() {
  # shellcheck disable=SC2016  # expanded by each rank's shell
  timeout 120 mpirun --allow-run-as-root --oversubscribe -np 2 sh -c 'cd "r$OMPI_COMM_WORLD_RANK" && exec "$0" "$@"' \
    "$RAYFORM_BIN" render grid.obj -o "$PWD/split.png" --size 32x24 -q
}
grid_bytes=$(wc -c <grid.obj)
for copy in missing shorter; do
  [ $copy = shorter ] && head -c 2000000 grid.obj >r1/grid.obj
  per_rank_folder >split.log 2>&1; rc=$?
  [ $rc -eq 1 ] || fail "split-$copy" "exit $rc, expected 1 (124: the ranks waited): $(cat split.log)"
  case $copy in
    missing) want="rank 1 of the MPI job cannot open it (No such file or directory), rank 0 reads $grid_bytes bytes" ;;
    shorter) want="rank 1 of the MPI job reads 2000000 bytes, rank 0 reads $grid_bytes bytes" ;;
  esac
  [ "$(grep -c "grid.obj: $want" split.log)" -eq 1 ] || fail "split-$copy" "expected one line '$want': $(cat split.log)"
  [ -e split.png ] && fail "split-$copy" "an output was written"
done
[ $failures -eq 0 ] && echo "ok   [split] a rank that cannot read the others' file stops the job at once, named"

# MPI is a plugin (librayform_mpi.so) opened only under a launcher: a rayform
# started on its own loads no MPI library, ranks under mpirun do. A plugin that
# cannot be opened (here: a file that is not one, named by RAYFORM_MPI_PLUGIN)
# stops the job with one line saying why, status 1, no output.
LD_DEBUG=files "$RAYFORM_BIN" --version >/dev/null 2>alone.libs || fail plugin "rayform --version failed"
grep -q 'libmpi\.so' alone.libs && fail plugin "a rayform started on its own loads libmpi"
LD_DEBUG=files mpi_run 2 --version >ranks.libs 2>&1 || fail plugin "mpirun -np 2 rayform --version failed"
[ "$(grep -c 'file=libmpi\.so\.[0-9]* \[0\];  needed by .*librayform_mpi\.so' ranks.libs)" -eq 2 ] ||
  fail plugin "2 ranks did not each load libmpi through librayform_mpi.so: $(grep -c libmpi ranks.libs) lines"
echo "not a shared library" >not-a-plugin.so
RAYFORM_MPI_PLUGIN=$PWD/not-a-plugin.so mpi_run 2 render "$course/2012/scene01_plane.txt" -o np.png >np.log 2>&1; rc=$?
[ $rc -ne 0 ] || fail plugin "a job whose MPI plugin cannot be opened exited 0"
grep -q '^rayform: error: started by an MPI launcher, but MPI cannot be used: .*not-a-plugin.so' np.log ||
  fail plugin "no message naming the plugin: $(cat np.log)"
[ -e np.png ] && fail plugin "an output was written without MPI"
[ $failures -eq 0 ] && echo "ok   [plugin] MPI loaded by ranks only; a broken plugin stops the job with a message"

# MPI starts on a thread of its own (distributed/ranks.h), the ranks taken at once
# from mpirun's environment. Without them there (as under a PMIx launcher,
# which gives the rank only) a rank waits for MPI to tell it; both ways give the
# one-process picture. An environment that disagrees with MPI (here both ranks
# told they are rank 0) stops the job with one line saying so.
before=$failures
env_run() {  # env_run ENV-ARGS... -- RAYFORM-ARGS...
  local e=()
  while [ "$1" != -- ]; do e+=("$1"); shift; done
  shift
  timeout 120 mpirun --allow-run-as-root --oversubscribe -np 2 env "${e[@]}" "$RAYFORM_BIN" "$@"
}
"$RAYFORM_BIN" render grid.obj -o "$PWD/env1.png" --size 40x30 -q || fail ranks-env "one process: exit $?"
env_run -u OMPI_COMM_WORLD_RANK -u OMPI_COMM_WORLD_SIZE -- render grid.obj -o "$PWD/env2.png" --size 40x30 -q \
  >env2.log 2>&1 || fail ranks-env "ranks from MPI: exit $?: $(cat env2.log)"
cmp -s env1.png env2.png || fail ranks-env "ranks from MPI: the picture differs from the one-process picture"
env_run OMPI_COMM_WORLD_RANK=0 -- render grid.obj -o "$PWD/env3.png" --size 40x30 -q >env3.log 2>&1; rc=$?
[ $rc -ne 0 ] || fail ranks-env "ranks that disagree with MPI: exit 0"
grep -q '^rayform: error: MPI says rank 1 of 2, the launcher.s environment rank 0 of 2' env3.log ||
  fail ranks-env "no line naming the ranks that disagree: $(cat env3.log)"
[ -e env3.png ] && fail ranks-env "ranks that disagree with MPI wrote an output"
[ $failures -eq $before ] && echo "ok   [ranks-env] ranks from mpirun's environment or from MPI; a disagreement stops the job"

# Progress from rank 0 only: mpirun on a terminal (a pty from util-linux
# `script`) draws the line rank 0 writes into its stderr pipe, with the share
# of the frame's tiles handed out; mpirun without a terminal gets none.
if command -v script >/dev/null; then
  before=$failures
  progress_run="timeout 120 mpirun --allow-run-as-root --oversubscribe -np 2 '$RAYFORM_BIN' render grid.obj -o '$PWD/progress.png' --size 320x240 --spp 4 --threads 1"
  script -qfec "$progress_run" /dev/null </dev/null >progress.log 2>&1 || fail progress "exit $?: $(cat -v progress.log)"
  [ "$(grep -c 'rendering done in [0-9]*:[0-9][0-9]' progress.log)" -eq 1 ] ||
    fail progress "expected one 'rendering done in' (rank 0's): $(cat -v progress.log)"
  grep -qE 'rendering +[0-9]+%  [0-9]+:[0-9]{2} elapsed' progress.log || fail progress "no percentage: $(cat -v progress.log)"
  [ -f progress.png ] || fail progress "no picture"
  mpi_run 2 render grid.obj -o "$PWD/quiet.png" --size 64x48 >quiet.log 2>&1 || fail progress "no terminal: exit $?"
  grep -q 'rendering' quiet.log && fail progress "mpirun without a terminal, yet a progress line: $(cat -v quiet.log)"
  [ $failures -eq $before ] && echo "ok   [progress] rank 0's progress line through mpirun on a terminal, none without one"
else
  echo "SKIPPED [progress]: script (util-linux) not found"
fi

echo "$failures failure(s)"
[ $failures -eq 0 ]
