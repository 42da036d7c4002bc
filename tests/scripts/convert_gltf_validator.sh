#!/usr/bin/env bash
# Every glTF/GLB `rayform convert` writes passes the Khronos glTF validator
# (npm gltf-validator, run by tests/tools/validate_gltf.js) with 0 errors and
# 0 warnings: the nine 2012 course scenes and the 2019 ones (cube map, bump)
# as .glb, .gltf and embedded .gltf, flattened and tessellated-only variants,
# the OBJ assets, the glTF sample assets, rayform's own test scenes
# (scenes/tests: shears, texture transforms, textured shapes without uvs), and
# glTF -> glTF again.
# Skips (77) when node is absent or the validator cannot be installed.
source "$(dirname "$0")/lib.sh"
require_shared
find_node_tools node_modules/gltf-validator/package.json

tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; expected=0
convert() {  # IN OUT [flags]
  local in=$1 out=$2; shift 2
  expected=$((expected + 1))
  if ! "$RAYFORM_BIN" convert "$in" "$out" "$@" >/dev/null 2>"$tmp/log"; then
    echo "FAIL: rayform convert $in $out $*: $(tail -c 300 "$tmp/log")"; fail=1
  fi
}
c12=$RAYFORM_SHARED/course/2012; c19=$RAYFORM_SHARED/course/2019; a=$RAYFORM_SHARED/assets
for f in "$c12"/scene*.txt; do
  n=$(basename "$f" .txt)
  convert "$f" "$tmp/c12_$n.glb"
  convert "$f" "$tmp/c12_$n.gltf"
  convert "$f" "$tmp/c12_${n}_embed.gltf" --embed
  convert "$f" "$tmp/c12_${n}_flat.glb" --flatten --sphere-segments 12
  convert "$f" "$tmp/c12_${n}_tess.glb" --tessellate-only --sphere-segments 9
done
for f in "$RAYFORM_SOURCE_DIR"/scenes/tests/*.txt "$RAYFORM_SOURCE_DIR"/scenes/default.txt; do  # our own test scenes
  n=$(basename "$f" .txt); d=(); [[ $n == *2019* ]] && d=(--dialect 2019)
  convert "$f" "$tmp/own_$n.glb" "${d[@]}"
  convert "$f" "$tmp/own_$n.gltf" "${d[@]}"
done
for f in "$c19"/scene*.txt; do
  n=$(basename "$f" .txt)
  convert "$f" "$tmp/c19_$n.glb" --dialect 2019
  convert "$f" "$tmp/c19_$n.gltf" --dialect 2019
done
for f in "$a"/duck/duck.obj "$a"/obj/spider/spider.obj "$a"/obj/cornell-box/cornell-box.obj "$a"/obj/suzanne.obj \
         "$a"/obj/teapot.obj "$a"/obj2gltf-edge-cases/box-complex-material/*.obj "$a"/obj2gltf-edge-cases/box-texture-options/*.obj \
         "$a"/obj2gltf-edge-cases/box-objects-groups-materials/*.obj "$a"/obj2gltf-edge-cases/concave/*.obj; do
  n=$(basename "$f" .obj)
  convert "$f" "$tmp/obj_$n.glb"
  convert "$f" "$tmp/obj_$n.gltf"
done
for f in "$a"/duck/duck.gltf "$a"/gltf/*/*.gltf "$a"/gltf/*/*.glb; do
  n=$(basename "$(dirname "$f")")_$(basename "$f"); n=${n%.*}  # BoxTextured comes three ways
  convert "$f" "$tmp/gltf_$n.glb"
  convert "$f" "$tmp/gltf_${n}_ext.gltf"
  convert "$f" "$tmp/gltf_${n}_flat.gltf" --flatten
done
# What we wrote, read and written again.
convert "$tmp/c12_scene08_c.glb" "$tmp/again_scene08_c.gltf"
convert "$tmp/obj_spider.gltf" "$tmp/again_spider.glb"

files=("$tmp"/*.gltf "$tmp"/*.glb)
node "$RAYFORM_SOURCE_DIR/tests/tools/validate_gltf.js" "${files[@]}" >"$tmp/report" 2>&1
vrc=$?
grep -v "errors 0, warnings 0," "$tmp/report"
clean=$(grep -c "errors 0, warnings 0," "$tmp/report")
echo "validator: $clean of ${#files[@]} files with 0 errors and 0 warnings (exit $vrc)"
[ "$clean" -eq "${#files[@]}" ] || fail=1
[ "${#files[@]}" -eq "$expected" ] || { echo "FAIL: ${#files[@]} files written, $expected conversions"; fail=1; }
exit $fail
