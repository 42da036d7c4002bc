#!/usr/bin/env bash
# OBJ -> glTF -> OBJ keeps the vertex, triangle, material and uv counts of
# every shared OBJ asset exactly: the counts of the scene read from the
# original (`convert --stats`, "read:" line) equal those read from the OBJ
# written back, both through .glb and through .gltf with external files; the
# written OBJ holds one `f` line per triangle and one `newmtl` per material.
source "$(dirname "$0")/lib.sh"
require_shared
a=$RAYFORM_SHARED/assets
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
counts() {  # the fields compared, from a "read:" line
  sed -n 's/^read: [^:]*: //p' | tr ',' '\n' | sed 's/^ *//' |
    grep -E '^(instances|mesh vertices|mesh uvs|mesh triangles|materials|textures) ' | tr '\n' ',' | sed 's/,$//'
}
for f in "$a"/duck/duck.obj "$a"/obj/*.obj "$a"/obj/*/*.obj; do
  n=$(basename "$f" .obj)
  for via in glb gltf; do
    mkdir -p "$tmp/$n-$via"; d=$tmp/$n-$via
    orig=$("$RAYFORM_BIN" convert "$f" "$d/a.$via" --stats 2>/dev/null | counts)
    "$RAYFORM_BIN" convert "$d/a.$via" "$d/b.obj" 2>/dev/null || { echo "FAIL: $n: .$via -> .obj"; fail=1; continue; }
    back=$("$RAYFORM_BIN" convert "$d/b.obj" "$d/c.glb" --stats 2>/dev/null | counts)
    tris=$(sed -n 's/.*mesh triangles \([0-9]*\).*/\1/p' <<<"$orig"); mats=$(sed -n 's/.*materials \([0-9]*\).*/\1/p' <<<"$orig")
    flines=$(grep -c '^f ' "$d/b.obj"); newmtl=$(grep -c '^newmtl ' "$d/b.mtl" 2>/dev/null || echo 0)
    if [ -z "$orig" ] || [ "$orig" != "$back" ] || [ "$flines" != "$tris" ] || [ "$newmtl" != "$mats" ]; then
      echo "FAIL: $n via .$via"; echo "  original: $orig"; echo "  back:     $back"
      echo "  written f lines $flines (want $tris), newmtl $newmtl (want $mats)"; fail=1
    else
      echo "ok: $n via .$via: $orig"
    fi
  done
done
exit $fail
