#!/usr/bin/env bash
# The camera options of `rayform render` (--look-from alone), on scenes
# written here and lit by ambient light only, so that every pixel is exactly
# the background (blue) or one sphere's colour:
#   two.txt  a course scene with its own camera at (0, 0, 10) looking down -z
#            at a red sphere at z = -2 and a green one at z = +2 (radius 1;
#            bounds (-1,-1,-3)..(1,1,3), centre the origin).
# Counts pixels of a colour with oiiotool --colorcount; pictures that must be
# the same are compared byte for byte. Needs no third-party data.
# The bad values of these options are checked in cli_errors.sh.
source "$(dirname "$0")/lib.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

cat >"$tmp/two.txt" <<'EOF'
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Lights { numLights 1 DirectionalLight { direction 0 -1 0 color 0 0 0 } }
Background { color 0 0 1 ambientLight 1 1 1 }
Materials { numMaterials 2 Material { diffuseColor 1 0 0 } Material { diffuseColor 0 1 0 } }
Group { numObjects 2
  MaterialIndex 0 Sphere { center 0 0 -2 radius 1 }
  MaterialIndex 1 Sphere { center 0 0 2 radius 1 } }
EOF
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }
ok() { echo "ok   [$1] $2"; }

# render NAME SCENE ARGS...: $tmp/NAME.png, 64x64; fails the check NAME when rayform does.
render() {
  local name=$1 scene=$2; shift 2
  "$RAYFORM_BIN" render "$tmp/$scene" -o "$tmp/$name.png" --size 64x64 -q "$@" >"$tmp/$name.log" 2>&1 ||
    { fail "$name" "rayform $* failed: $(cat "$tmp/$name.log")"; return 1; }
}
# count IMAGE [REGION]: "RED GREEN BLUE", pixels of each colour (in REGION, WxH+X+Y).
count() {
  oiiotool "$1" ${2:+--cut "$2"} --colorcount:eps=0.02,0.02,0.02 "1,0,0;0,1,0;0,0,1" |
    awk '{ printf "%s%s", sep, $1; sep = " " } END { print "" }'
}
# expect_counts NAME IMAGE REGION TEST...: each TEST is an awk condition on r, g, b.
expect_counts() {
  local name=$1 image=$2 region=$3 counts; shift 3
  counts=$(count "$image" "$region")
  for t in "$@"; do
    awk -v c="$counts" "BEGIN { split(c, n, \" \"); r = n[1]; g = n[2]; b = n[3]; exit !($t) }" ||
      { fail "$name" "${region:-whole picture}: red green blue = $counts, expected $t"; return 1; }
  done
  ok "$name" "${region:-whole picture}: red green blue = $counts"
}
same() {
  if cmp -s "$tmp/$2.png" "$tmp/$3.png"; then ok "$1" "$2.png and $3.png are identical"
  else fail "$1" "$2.png and $3.png differ"; fi
}
L=32x64+0+0 R=32x64+32+0 TOP=64x32+0+0 BOTTOM=64x32+0+32

# --look-from alone aims at the centre of the bounds (the file's camera looked
# down -z; keeping that direction from (6, 4, 6) saw nothing but background).
if render look-from two.txt --look-from 6,4,6 && render look-from-at two.txt --look-from 6,4,6 --look-at 0,0,0; then
  expect_counts look-from "$tmp/look-from.png" "" "r > 150" "g > 150"
  same look-from look-from look-from-at
fi
# Straight down from above: the camera's up (+y) is parallel to the view, so
# -z becomes up: the red sphere (z = -2) at the top, the green one below.
if render look-down two.txt --look-from 0,8,0 && render look-down-up two.txt --look-from 0,8,0 --look-at 0,0,0 --up 0,0,-1; then
  expect_counts look-down "$tmp/look-down.png" $TOP "r > 150" "g == 0"
  expect_counts look-down "$tmp/look-down.png" $BOTTOM "g > 150" "r == 0"
  same look-down look-down look-down-up
fi
# --look-at alone keeps the position: from (0, 0, 10) towards the red sphere's side.
if render look-at two.txt --look-at 0,0,0 && render look-at-file two.txt; then
  same look-at look-at look-at-file
fi

# An explicit --up parallel to the view stays an error (exit 1, no picture).
"$RAYFORM_BIN" render "$tmp/two.txt" -o "$tmp/up.png" --look-from 0,8,0 --up 0,1,0 -q >"$tmp/up.log" 2>&1
rc=$?
if [ $rc -eq 1 ] && grep -q -- "--up must not be parallel" "$tmp/up.log" && [ ! -e "$tmp/up.png" ]; then
  ok up-parallel "exit 1: $(cat "$tmp/up.log")"
else fail up-parallel "exit $rc, picture $([ -e "$tmp/up.png" ] && echo written || echo absent): $(cat "$tmp/up.log")"; fi

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all camera option checks passed"
