#!/usr/bin/env bash
# Each of the nine 2012 course scenes converted to .glb and back to a course
# .txt (meshes and textures written beside it) renders like the original by
# the course-parity rule: colour, depth and normals with the course command
# line, at most 0.5 % of pixels over 2/255 (../shared/tools/course-parity).
# The .txt written back must also be the one a direct .txt -> .txt gives.
source "$(dirname "$0")/lib.sh"
require_shared
c12=$RAYFORM_SHARED/course/2012
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/glb" "$tmp/back" "$tmp/direct"
fail=0
while read -r name _; do
  [ -n "$name" ] || continue
  "$RAYFORM_BIN" convert "$c12/$name.txt" "$tmp/glb/$name.glb" 2>/dev/null || { echo "FAIL: $name.txt -> .glb"; fail=1; }
  # glb -> txt must not lose anything the course can hold: no notes at all.
  "$RAYFORM_BIN" convert "$tmp/glb/$name.glb" "$tmp/back/$name.txt" 2>"$tmp/notes" || { echo "FAIL: $name.glb -> .txt"; fail=1; }
  if [ -s "$tmp/notes" ]; then echo "FAIL: $name.glb -> .txt reported:"; cat "$tmp/notes"; fail=1; fi
  "$RAYFORM_BIN" convert "$c12/$name.txt" "$tmp/direct/$name.txt" 2>/dev/null || fail=1
  cmp -s "$tmp/back/$name.txt" "$tmp/direct/$name.txt" || { echo "FAIL: $name: .txt via .glb differs from .txt -> .txt"; diff "$tmp/direct/$name.txt" "$tmp/back/$name.txt" | head -20; fail=1; }
done < "$c12/reference/MANIFEST.txt"
"$RAYFORM_SHARED/tools/course-parity" "$RAYFORM_BIN" "$tmp/back" "$c12/reference" || fail=1
exit $fail
