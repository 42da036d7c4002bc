#!/usr/bin/env bash
# What the ranks of one spread frame do before they render (docs/distributed.md):
# - MPI's start overlaps the load: a rank does not wait for MPI (nor for a
#   rank that starts late) before it has loaded the scene; the ranks meet at
#   the gate (the input file's size and whether each loaded) only before the
#   first exchange or at the readiness agreement;
# - the textures and cube-map faces are decoded shared: each rank opens and
#   decodes its share of the 2019 arch scene's six faces, and the picture is
#   the one-process picture, byte for byte;
# - a course scene (no exchange in its load) that a rank cannot open, or
#   reads shorter, still stops the job with one line from rank 0, and a face
#   that fails to decode on one rank's share fails the job with the error one
#   process gives.
# shellcheck disable=SC2016  # the per-rank scripts expand in each rank's shell
source "$(dirname "$0")/lib.sh"
require_mpi
require_shared
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

arch=$RAYFORM_SHARED/course/2019/scene07_arch.txt
plane=$RAYFORM_SHARED/course/2012/scene01_plane.txt
# Runs rayform as 2 ranks, each through `sh -c SCRIPT` (rank number in $r), under a time limit.
per_rank() {  # per_rank SCRIPT RAYFORM-ARGS...
  local script=$1; shift
  timeout 120 mpirun --allow-run-as-root --oversubscribe -np 2 \
    sh -c 'r=$OMPI_COMM_WORLD_RANK; '"$script"' "$0" "$@"' "$RAYFORM_BIN" "$@"
}

# 1. Rank 1 starts 0.8 s late, so MPI cannot be up on rank 0 before then:
# rank 0 loads the scene meanwhile (its load stage a few milliseconds, not the
# 0.8 s it waited when the ranks agreed on the file right after the load).
before=$failures
per_rank 'if [ "$r" = 1 ]; then sleep 0.8; fi; exec' -input "$plane" -size 40 30 -output "$PWD/late.png" -stats \
  >late.log 2>&1 || fail late-rank "exit $?: $(cat late.log)"
load0=$(sed -nE 's/^stats: rank 0 of 2: .* load ([0-9.e+-]+) s, .*/\1/p' late.log)
[ -n "$load0" ] || fail late-rank "no stats line for rank 0: $(cat late.log)"
if [ -n "$load0" ] && ! awk -v l="$load0" 'BEGIN {exit !(l < 0.4)}'; then
  fail late-rank "rank 0's load took $load0 s: it waited for the late rank"
fi
"$RAYFORM_BIN" -input "$plane" -size 40 30 -output "$PWD/late1.png" || fail late-rank "one process: exit $?"
cmp -s late.png late1.png || fail late-rank "the picture differs from the one-process picture"
[ $failures -eq $before ] && echo "ok   [late-rank] rank 0 loaded in $load0 s while rank 1 was starting"

# 2. The arch scene's cube map (six 1024x1024 PNG faces) decoded shared.
before=$failures
arch_args=(-input "$arch" -size 64 48 -shadows -bounces 3 -spp 2)
"$RAYFORM_BIN" "${arch_args[@]}" -output "$PWD/arch1.png" || fail arch "one process: exit $?"
for np in 2 3; do
  mpi_run "$np" "${arch_args[@]}" -output "$PWD/arch$np.png" >"arch$np.log" 2>&1 ||
    fail arch "$np ranks: exit $?: $(cat "arch$np.log")"
  cmp -s arch1.png "arch$np.png" || fail arch "$np ranks: the picture differs from the one-process picture"
done
if command -v strace >/dev/null; then
  per_rank 'exec strace -f -qq -e trace=openat -o "$PWD/trace$r"' "${arch_args[@]}" -output "$PWD/arch-traced.png" \
    >traced.log 2>&1 || fail arch "2 ranks under strace: exit $?: $(cat traced.log)"
  for r in 0 1; do
    faces=$(grep -E 'church/[a-z]+\.png' "trace$r" | grep -v ENOENT | grep -oE '[a-z]+\.png' | sort -u | tr '\n' ' ')
    [ "$(echo "$faces" | wc -w)" -eq 3 ] || fail arch "rank $r opened the faces $faces, not 3 of the 6"
  done
  cmp -s arch1.png arch-traced.png || fail arch "under strace: the picture differs"
else
  echo "SKIPPED [arch: faces per rank]: strace not found"
fi
[ $failures -eq $before ] && echo "ok   [arch] the cube map decoded shared by 2 and 3 ranks: the one-process picture"

# 3. A course scene (its load makes no exchange) missing on one rank, or read
# shorter: one line from rank 0 naming the rank, status 1, no output.
before=$failures
mkdir -p r0 r1
plane_bytes=$(wc -c <"$plane")
for copy in missing1 missing0 shorter; do
  rm -f r0/plane.txt r1/plane.txt split.png
  case $copy in
    missing1) cp "$plane" r0/plane.txt
      want="rank 1 of the MPI job cannot open it (No such file or directory), rank 0 reads $plane_bytes bytes" ;;
    missing0) cp "$plane" r1/plane.txt
      want="rank 1 of the MPI job reads $plane_bytes bytes, rank 0 cannot open it (No such file or directory)" ;;
    shorter) cp "$plane" r0/plane.txt; head -c 300 "$plane" >r1/plane.txt
      want="rank 1 of the MPI job reads 300 bytes, rank 0 reads $plane_bytes bytes" ;;
  esac
  per_rank 'cd "r$r" && exec' -input plane.txt -size 32 24 -output "$PWD/split.png" >split.log 2>&1; rc=$?
  [ $rc -eq 1 ] || fail "split-$copy" "exit $rc, expected 1 (124: the ranks waited): $(cat split.log)"
  [ "$(grep -c "plane.txt: $want" split.log)" -eq 1 ] || fail "split-$copy" "expected one line '$want': $(cat split.log)"
  [ "$(grep -c 'error' split.log)" -eq 1 ] || fail "split-$copy" "expected one error line: $(cat split.log)"
  [ -e split.png ] && fail "split-$copy" "an output was written"
done
[ $failures -eq $before ] && echo "ok   [split] a course scene missing or shorter on a rank stops the job, named once"

# 4. A face that cannot be decoded (a truncated PNG): every rank fails with
# the error one process gives, printed once; status 1; no output.
before=$failures
mkdir -p broken/tex
cp "$arch" broken/ && cp -r "$(dirname "$arch")/tex/church" broken/tex/ && cp -r "$(dirname "$arch")/models" broken/ && chmod -R u+w broken
head -c 5000 "$(dirname "$arch")/tex/church/front.png" >broken/tex/church/front.png
"$RAYFORM_BIN" -input broken/scene07_arch.txt -size 32 24 -output "$PWD/broken1.png" >broken1.log 2>&1; rc=$?
[ $rc -eq 1 ] || fail broken-face "one process: exit $rc, expected 1: $(cat broken1.log)"
grep -q 'front.png' broken1.log || fail broken-face "one process: no line naming front.png: $(cat broken1.log)"
for np in 2 3; do
  mpi_run "$np" -input broken/scene07_arch.txt -size 32 24 -output "$PWD/broken$np.png" >"broken$np.log" 2>&1; rc=$?
  [ $rc -eq 1 ] || fail broken-face "$np ranks: exit $rc, expected 1: $(cat "broken$np.log")"
  diff <(grep error broken1.log) <(grep error "broken$np.log") >/dev/null ||
    fail broken-face "$np ranks: not the one-process error once: $(cat "broken$np.log")"
  [ -e "broken$np.png" ] && fail broken-face "$np ranks: an output was written"
done
[ $failures -eq $before ] && echo "ok   [broken-face] a face that fails on one rank's share: the one-process error, once"

echo "$failures failure(s)"
[ $failures -eq 0 ]
