#!/usr/bin/env bash
# A second opinion: Open Asset Import Library (Debian assimp-utils) opens
# every .glb, .gltf and .obj `rayform convert` writes (and the OBJ meshes a
# course .txt output names) and counts the triangles rayform says it stored
# (`convert --stats`). Where assimp drops degenerate faces of a source it can
# read itself, it must drop the same from our file: its count for the source.
# Skips (77) when assimp is not installed.
source "$(dirname "$0")/lib.sh"
require_shared
command -v assimp >/dev/null || { echo "SKIPPED: assimp not found (apt-get install assimp-utils)"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; checked=0
faces() { timeout 120 assimp info "$1" 2>/dev/null | sed -n 's/^Faces: *//p'; }
check() {  # SOURCE OUT
  local src=$1 out=$2 stats stored want got files
  stats=$("$RAYFORM_BIN" convert "$src" "$out" --stats 2>/dev/null) || { echo "FAIL: convert $src $out"; fail=1; return; }
  stored=$(sed -n 's/.*stored triangles \([0-9]*\).*/\1/p' <<<"$stats")
  want=$stored
  case $src in *.obj|*.gltf|*.glb)
    read_tris=$(sed -n 's/.*mesh triangles \([0-9]*\),.*/\1/p' <<<"$stats")
    # Only when the source has one mesh use per mesh (no instancing) is assimp's source count comparable.
    if [ "$stored" = "$read_tris" ]; then src_faces=$(faces "$src"); [ -n "$src_faces" ] && want=$src_faces; fi ;;
  esac
  if [[ $out == *.txt ]]; then
    got=0
    files=$(sed -n 's/^  \(.*\.obj\)$/\1/p' <<<"$stats")
    for f in $files; do n=$(faces "$f"); got=$((got + ${n:-0})); done
  else
    got=$(faces "$out")
  fi
  checked=$((checked + 1))
  if [ "$got" != "$want" ]; then echo "FAIL: $(basename "$(dirname "$out")")/$(basename "$out"): assimp counts ${got:-nothing}, want $want (stored $stored)"; fail=1
  else echo "ok: $(basename "$(dirname "$out")")/$(basename "$out"): $got triangles"; fi
}
c12=$RAYFORM_SHARED/course/2012; a=$RAYFORM_SHARED/assets
for f in "$c12"/scene*.txt "$a"/duck/duck.obj "$a"/obj/spider/spider.obj "$a"/obj/cornell-box/cornell-box.obj \
         "$a"/obj/suzanne.obj "$a"/duck/duck.gltf "$a"/gltf/2CylinderEngine-glTF-Binary/2CylinderEngine.glb \
         "$a"/gltf/BoxTextured-glTF/BoxTextured.gltf; do
  n=$(basename "$f"); n=${n%.*}
  mkdir -p "$tmp/$n"
  for e in glb gltf obj txt; do check "$f" "$tmp/$n/out.$e"; done
done
echo "$checked files checked"
exit $fail
