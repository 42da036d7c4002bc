#!/usr/bin/env bash
# The 2012 assignment-5 scenes (dialect a5): scenes 10, 11 and 13 against the
# course solution's pictures (../shared/tools/course-parity; 2/255 on at most
# 0.5 % of pixels), and scenes 06 and 12, which have no reference, rendered
# with the course's own command line (no -dialect: detected) at the reference
# size and at 320x240. Also the detection itself: the a5 scenes with a .bmp
# cube map read as a5, scene13_diamond (refractionIndex, with falloff) too,
# rendered without -dialect; the 2019 scene06 (a .png cube map) as 2019.
source "$(dirname "$0")/lib.sh"
require_shared
a5="$RAYFORM_SHARED/course/2012-a5"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
"$RAYFORM_SHARED/tools/course-parity" "$RAYFORM_BIN" "$a5" "$a5/reference" || failures=$((failures + 1))

tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for scene in scene06_bunny_1k scene12_vase; do
  for size in "200 200" "320 240"; do
    out="$tmp/${scene}_${size/ /x}.png"
    if ! (cd "$a5" && "$RAYFORM_BIN" -input "$scene.txt" -size "${size% *}" "${size#* }" -output "$out" -shadows -quiet); then
      fail "$scene at $size"
      continue
    fi
    got=$(oiiotool "$out" --echo "{TOP.width} {TOP.height}" 2>/dev/null)
    [ "$got" = "$size" ] || fail "$scene: picture is '$got', not $size"
    echo "ok   $scene at ${size/ /x}"
  done
done

# -bounces defaults to 4 in a5 (the same picture as -bounces 4, not as 0),
# and the modern command line gives the course's picture.
(cd "$a5" && "$RAYFORM_BIN" -input scene10_sphere.txt -size 64 64 -output "$tmp/default.png" -shadows -quiet &&
  "$RAYFORM_BIN" -input scene10_sphere.txt -size 64 64 -output "$tmp/b4.png" -shadows -bounces 4 -quiet &&
  "$RAYFORM_BIN" -input scene10_sphere.txt -size 64 64 -output "$tmp/b0.png" -shadows -bounces 0 -quiet &&
  "$RAYFORM_BIN" render scene10_sphere.txt -o "$tmp/modern.png" --size 64x64 --shadows --dialect a5 -q) ||
  fail "scene10 at 64x64"
idiff -q "$tmp/default.png" "$tmp/b4.png" >/dev/null 2>&1 || fail "a5 without -bounces differs from -bounces 4"
idiff -q "$tmp/default.png" "$tmp/b0.png" >/dev/null 2>&1 && fail "a5 without -bounces is the -bounces 0 picture"
idiff -q "$tmp/default.png" "$tmp/modern.png" >/dev/null 2>&1 || fail "rayform render --dialect a5 differs from the course command line"
echo "ok   -bounces defaults to 4 in a5; render --dialect a5 gives the same picture"

# The course's command line without -dialect: scene13_diamond (refractionIndex
# and point lights with falloff) is detected as a5 and gives the reference
# picture, and at 160x160 the same picture as -dialect a5.
if (cd "$a5" && "$RAYFORM_BIN" -input scene13_diamond.txt -size 200 200 -output "$tmp/diamond.png" -shadows -bounces 4 -quiet &&
  "$RAYFORM_BIN" -input scene13_diamond.txt -size 160 160 -output "$tmp/diamond160.png" -shadows -bounces 4 -quiet &&
  "$RAYFORM_BIN" -input scene13_diamond.txt -size 160 160 -output "$tmp/diamond160_a5.png" -shadows -bounces 4 -dialect a5 -quiet); then
  before=$failures
  idiff -fail 0.0079 -failpercent 0.5 "$a5/reference/scene13_diamond.png" "$tmp/diamond.png" >/dev/null 2>&1 ||
    fail "scene13_diamond without -dialect differs from the a5 reference"
  idiff -q "$tmp/diamond160_a5.png" "$tmp/diamond160.png" >/dev/null 2>&1 ||
    fail "scene13_diamond at 160x160 without -dialect differs from -dialect a5"
  [ $failures -eq $before ] && echo "ok   scene13_diamond without -dialect renders as a5"
else
  fail "scene13_diamond without -dialect"
fi

dialect_of() { (cd "$(dirname "$1")" && "$RAYFORM_BIN" info "$(basename "$1")") | sed -n 's/.*dialect \([0-9a-z]*\).*/\1/p'; }
for scene in scene06_bunny_1k scene10_sphere scene11_cube scene12_vase scene13_diamond; do
  d=$(dialect_of "$a5/$scene.txt")
  [ "$d" = a5 ] || fail "$scene detected as '$d', not a5"
done
d=$(dialect_of "$RAYFORM_SHARED/course/2019/scene06_bunny_1k.txt")
[ "$d" = 2019 ] || fail "the 2019 scene06_bunny_1k detected as '$d', not 2019"
for scene in "$RAYFORM_SHARED"/course/2012/scene*.txt; do
  d=$(dialect_of "$scene")
  [ "$d" = 2012 ] || fail "$(basename "$scene") detected as '$d', not 2012"
done

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all a5 checks passed"
