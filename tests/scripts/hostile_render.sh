#!/usr/bin/env bash
# Hostile input to the renderer and the command line (issue 33): each case
# makes its input here and must end within its time (timeout) with exit 0
# and the right picture, or exit 1/2 with one line; nothing written outside
# the asked place; no control byte echoed. Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }
pass() { echo "PASS [$1]"; }

# The camera inside a mirror sphere, lit from inside.
cat >mirror.txt <<'SCENE'
PerspectiveCamera { center 0 0 0 direction 0 0 -1 up 0 1 0 angle 60 }
Lights { numLights 1 PointLight { position 0 0.5 0 color 0.1 0.1 0.1 } }
Materials { numMaterials 1 PhongMaterial { diffuseColor 0.1 0.1 0.1 specularColor 0.9 0.9 0.9 shininess 20 } }
Background { color 0.2 0.1 0.6 ambientLight 0.02 0.02 0.02 }
Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 2 } }
SCENE

# 1. --bounces 100000 (and the course -bounces): the depth is capped at 64
# with one note; the picture is the one of --bounces 64.
timeout 60 "$RAYFORM_BIN" render mirror.txt --size 32x32 --bounces 64 -o b64.png 2>b64.err
timeout 60 "$RAYFORM_BIN" render mirror.txt --size 32x32 --bounces 100000 -o big.png 2>big.err; rc=$?
if [ $rc -ne 0 ]; then fail bounces "render --bounces 100000 exited $rc: $(head -c 300 big.err)"
elif ! cmp -s b64.png big.png; then fail bounces "--bounces 100000 differs from --bounces 64"
elif [ "$(grep -c 'note: bounces 100000: .* 64 deep at most' big.err)" != 1 ] || [ "$(wc -l <big.err)" != 1 ]; then
  fail bounces "expected one note, got: $(cat big.err)"
else pass bounces; fi
timeout 60 "$RAYFORM_BIN" -input mirror.txt -size 32 32 -bounces 20000 -output course.png 2>course.err; rc=$?
timeout 60 "$RAYFORM_BIN" -input mirror.txt -size 32 32 -bounces 64 -output course64.png 2>/dev/null
if [ $rc -ne 0 ]; then fail course-bounces "-bounces 20000 exited $rc: $(head -c 300 course.err)"
elif ! cmp -s course64.png course.png; then fail course-bounces "-bounces 20000 differs from -bounces 64"
else pass course-bounces; fi
# Below the cap the depth still counts: 8 and 64 differ for this mirror.
timeout 60 "$RAYFORM_BIN" render mirror.txt --size 32x32 --bounces 8 -o b8.png 2>/dev/null
if cmp -s b8.png b64.png; then fail bounces-below-cap "--bounces 8 and 64 give the same picture"; else pass bounces-below-cap; fi

# 8. Copies of one triangle are merged at prepare: 300000 of them render as
# fast as one, to the same picture (before: each ray tested every copy).
printf 'v -1 -1 0\nv 1 -1 0\nv 0 1 0\n' >one.obj
cp one.obj copies.obj
printf 'f 1 2 3\n' >>one.obj
awk 'BEGIN { for (i = 0; i < 300000; ++i) print "f 1 2 3" }' >>copies.obj
"$RAYFORM_BIN" render one.obj --size 64x64 -q -o one.png
timeout 10 "$RAYFORM_BIN" render copies.obj --size 64x64 -q -o copies.png 2>copies.err; rc=$?
if [ $rc -ne 0 ]; then fail copies "exited $rc (124: over 10 s): $(head -c 300 copies.err)"
elif ! cmp -s one.png copies.png; then fail copies "300000 copies of a triangle differ from one"
else pass copies; fi

# 9. render refuses to write over one of the scene's inputs (its texture
# here), as convert does: exit 1, one line, the texture unchanged.
mkdir tex
"$RAYFORM_BIN" render mirror.txt --size 4x4 -q -o tex/checker.bmp
cp tex/checker.bmp checker.orig
printf 'newmtl m\nKd 1 1 1\nmap_Kd checker.bmp\n' >tex/materials.mtl
printf 'mtllib materials.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n' \
  >tex/materials.obj
(cd tex && "$RAYFORM_BIN" render materials.obj --size 8x8 -q -o checker.bmp) 2>own.err; rc=$?
if [ $rc -ne 1 ] || [ "$(wc -l <own.err)" != 1 ] || ! grep -q "would replace checker.bmp" own.err; then
  fail own-texture "expected exit 1 and one line, got $rc: $(cat own.err)"
elif ! cmp -s tex/checker.bmp checker.orig; then fail own-texture "the texture was replaced"
else pass own-texture; fi

# 11. An input named '...txt' has the stem '..': {stem} becomes '__', so
# 'out/{stem}/color.png' stays in out/ (before: ./color.png).
mkdir -p stems/out
cp mirror.txt stems/...txt
(cd stems && "$RAYFORM_BIN" render ...txt --size 4x4 -q -o 'out/{stem}/color.png') 2>stem.err; rc=$?
if [ -e stems/color.png ] || [ -e stems/out/color.png ]; then fail stem "written outside out/{stem}/: $(cd stems && find . -name color.png)"
elif [ $rc -ne 2 ] || [ "$(wc -l <stem.err)" != 2 ] || ! grep -q "folder 'out/__' does not exist" stem.err; then
  fail stem "expected exit 2 naming out/__, got $rc: $(cat stem.err)"
else
  mkdir stems/out/__
  (cd stems && "$RAYFORM_BIN" render ...txt --size 4x4 -q -o 'out/{stem}/color.png') 2>stem.err; rc=$?
  if [ $rc -ne 0 ] || [ ! -s stems/out/__/color.png ]; then fail stem "out/__/color.png not written ($rc): $(cat stem.err)"
  else pass stem; fi
fi

# 12. Names from files reach stderr escaped: ESC, BEL and C1 controls as
# \u001b, bytes that are not UTF-8 as U+FFFD (in notes, errors, batch errors).
mkdir names
evil=$'evil\e]0;pwned\a\xff\xc2\x9b'
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"names/$evil.obj"
printf 'v 0 0 0\n' >"names/bad$evil.obj"
(cd names && "$RAYFORM_BIN" render "$evil.obj" --size 4x4 -o o.png; "$RAYFORM_BIN" render "bad$evil.obj" -o o.png
 "$RAYFORM_BIN" render "$evil.obj" "bad$evil.obj" --size 4x4 -o '{stem}.png') 2>names.err
if LC_ALL=C grep -q $'[\x01-\x09\x0b-\x1f\x7f]' names.err || LC_ALL=C grep -q $'\xc2[\x80-\x9f]' names.err; then
  fail names "a control byte reached stderr: $(od -c names.err | head -5)"
elif ! iconv -f UTF-8 -t UTF-8 names.err >/dev/null 2>&1; then fail names "stderr is not UTF-8"
elif [ "$(grep -c 'evil\\u001b\]0;pwned\\u0007'$'\xef\xbf\xbd''\\u009b' names.err)" -lt 4 ]; then
  fail names "expected the escaped name in the notes and errors: $(cat names.err)"
else pass names; fi

# 10. A mesh named with 300 bytes: convert names its side file with the
# name's start and a hash (before: "File name too long").
mkdir long
long_name=$(printf 'n%.0s' $(seq 300))
printf 'o %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' "$long_name" >long/long.obj
"$RAYFORM_BIN" convert long/long.obj long/out.txt 2>long.err; rc=$?
side=$(cd long && ls out_*.obj 2>/dev/null)
if [ $rc -ne 0 ]; then fail long-name "convert exited $rc: $(head -c 300 long.err)"
elif ! [[ "$side" =~ ^out_n{87}_[0-9a-f]{8}\.obj$ ]]; then fail long-name "side file '$side'"
elif ! grep -q "$side" long/out.txt; then fail long-name "out.txt does not name $side"
else pass long-name; fi
# The same for a glTF mesh name.
cat >long/long.gltf <<GLTF
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"name":"$long_name","primitives":[{"attributes":{"POSITION":0}}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}
GLTF
"$RAYFORM_BIN" convert long/long.gltf long/g.txt 2>long.err; rc=$?
if [ $rc -ne 0 ] || [ -z "$(cd long && ls g_n*_[0-9a-f]*.obj 2>/dev/null)" ]; then
  fail long-gltf-name "convert exited $rc: $(head -c 300 long.err)"
else pass long-gltf-name; fi

# 7. --frames 1000000000: the jobs are made as they are rendered, so frames
# come out at once (before: none after 15 s, memory growing by 140 MB/s).
mkdir spin
timeout 5 "$RAYFORM_BIN" render mirror.txt --size 8x8 --frames 1000000000 -o 'spin/m_{frame}.png' 2>frames.err; rc=$?
if [ $rc -ne 124 ]; then fail frames "expected to be still rendering after 5 s (124), got $rc: $(head -c 300 frames.err)"
elif [ ! -s spin/m_0000.png ] || [ ! -s spin/m_0001.png ]; then fail frames "no frame written in 5 s"
else pass frames; fi
# Two inputs of one stem still collide, at the first frame.
mkdir -p other; cp mirror.txt other/mirror.txt
"$RAYFORM_BIN" render mirror.txt other/mirror.txt --frames 3 -o 'spin/{stem}_{frame}.png' 2>collide.err; rc=$?
if [ $rc -ne 2 ] || ! grep -q "would both write spin/mirror_0000.png" collide.err; then
  fail frames-collide "expected exit 2 naming spin/mirror_0000.png, got $rc: $(cat collide.err)"
else pass frames-collide; fi

[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "all cases passed"
