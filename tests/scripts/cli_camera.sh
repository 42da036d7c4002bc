#!/usr/bin/env bash
# The camera options of `rayform render` (--look-from alone, --frame,
# --orbit), on scenes written here and lit by ambient light only, so that
# every pixel is exactly the background (blue) or one sphere's colour:
#   two.txt  a course scene with its own camera at (0, 0, 10) looking down -z
#            at a red sphere at z = -2 and a green one at z = +2 (radius 1;
#            bounds (-1,-1,-3)..(1,1,3), centre the origin).
#   two.obj  the same two spheres' bounding boxes as an OBJ (no camera).
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
# Two unit cubes (z = -3..-1 and 1..3) in one OBJ: the same bounds.
{
  for z0 in -3 1; do
    z1=$((z0 + 2))
    for v in "-1 -1 $z0" "1 -1 $z0" "-1 1 $z0" "1 1 $z0" "-1 -1 $z1" "1 -1 $z1" "-1 1 $z1" "1 1 $z1"; do echo "v $v"; done
  done
  for o in 0 8; do
    for f in "1 2 4 3" "5 7 8 6" "1 5 6 2" "3 4 8 7" "1 3 7 5" "2 6 8 4"; do
      set -- $f
      echo "f $(($1 + o)) $(($2 + o)) $(($3 + o)) $(($4 + o))"
    done
  done
} >"$tmp/two.obj"

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

# --orbit AZ,EL: AZ = 0 looks from +z (green in front, red hidden behind it),
# 180 from -z, 90 from +x (green, at z = +2, on the left), -90 from -x.
if render orbit-0 two.txt --orbit 0,0; then expect_counts orbit-0 "$tmp/orbit-0.png" "" "g > 400" "r == 0"; fi
if render orbit-180 two.txt --orbit 180,0; then expect_counts orbit-180 "$tmp/orbit-180.png" "" "r > 400" "g == 0"; fi
if render orbit-90 two.txt --orbit 90,0; then
  expect_counts orbit-90 "$tmp/orbit-90.png" $L "g > 150" "r == 0"
  expect_counts orbit-90 "$tmp/orbit-90.png" $R "r > 150" "g == 0"
fi
if render orbit-270 two.txt --orbit -90,0 && render orbit-270b two.txt --orbit 270,0; then
  expect_counts orbit-270 "$tmp/orbit-270.png" $L "r > 150" "g == 0"
  expect_counts orbit-270 "$tmp/orbit-270.png" $R "g > 150" "r == 0"
  # 270 and -90 are the same place, up to the rounding of sin and cos.
  expect_counts orbit-270b "$tmp/orbit-270b.png" $L "r > 150" "g == 0"
fi
# EL above the horizon from the +z side: the green sphere low, the red one
# behind it peeks out above.
if render orbit-up two.txt --orbit 0,30; then
  expect_counts orbit-up "$tmp/orbit-up.png" $TOP "r > 20"
  expect_counts orbit-up "$tmp/orbit-up.png" $BOTTOM "g > 100" "r == 0"
fi
# The default distance frames the whole box: every sphere pixel lies inside
# the picture's outermost rows and columns, from any side.
for o in 0,0 90,0 45,20 200,-60; do
  if render orbit-edge two.txt --orbit $o; then
    all=$(count "$tmp/orbit-edge.png" | cut -d' ' -f1,2) inner=$(count "$tmp/orbit-edge.png" 62x62+1+1 | cut -d' ' -f1,2)
    if [ "$all" = "$inner" ] && [ "$all" != "0 0" ]; then ok "orbit $o framed" "red green = $all, none on the edge"
    else fail "orbit $o framed" "red green = $all, inside the edge $inner"; fi
  fi
done
# DIST from the centre: the green sphere (z = 2) is 8 away at DIST 10 and 18
# at DIST 20, so it covers (18 / 8)^2 = 5.06 times fewer pixels (within 20 %).
if render orbit-d10 two.txt --orbit 0,0,10 && render orbit-d20 two.txt --orbit 0,0,20; then
  near=$(count "$tmp/orbit-d10.png" | cut -d' ' -f2) far=$(count "$tmp/orbit-d20.png" | cut -d' ' -f2)
  if awk -v n="$near" -v f="$far" 'BEGIN { exit !(f > 0 && n / f > 4.05 && n / f < 6.1) }'; then
    ok orbit-dist "green pixels at distance 10: $near, at 20: $far"
  else fail orbit-dist "green pixels at distance 10: $near, at 20: $far (expected a ratio near 5.06)"; fi
fi

# --frame is the default camera, which is the orbit at 0,0: the same picture,
# for a course file (its own camera replaced) and for an OBJ without a camera.
if render frame two.txt --frame && render frame-orbit two.txt --orbit 0,0; then same frame frame frame-orbit; fi
if render obj-default two.obj && render obj-frame two.obj --frame && render obj-orbit two.obj --orbit 0,0; then
  same obj-frame obj-default obj-frame
  same obj-orbit obj-default obj-orbit
fi
# Other camera options adjust the framed camera: --frame --look-from is
# --look-from alone (the file's camera replaced only in its projection).
if render frame-look-from two.txt --frame --look-from 6,4,6; then
  expect_counts frame-look-from "$tmp/frame-look-from.png" "" "r > 150" "g > 150"
fi

# An explicit --up parallel to the view stays an error (a usage error: exit 2, no picture).
"$RAYFORM_BIN" render "$tmp/two.txt" -o "$tmp/up.png" --look-from 0,8,0 --up 0,1,0 -q >"$tmp/up.log" 2>&1
rc=$?
if [ $rc -eq 2 ] && grep -q -- "--up must not be parallel" "$tmp/up.log" && [ ! -e "$tmp/up.png" ]; then
  ok up-parallel "exit 2: $(cat "$tmp/up.log")"
else fail up-parallel "exit $rc, picture $([ -e "$tmp/up.png" ] && echo written || echo absent): $(cat "$tmp/up.log")"; fi

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all camera option checks passed"
