#!/usr/bin/env bash
# Golden test: the 2019 dialect's scenes 01-05 against its solution's pictures
# at 200x200 and at the course's own 800x800. Scenes 06-07 (reflections,
# shadows, cube map) are checked by course_parity_2019_full.sh once supported.
source "$(dirname "$0")/lib.sh"
require_shared
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
status=0
for ref in reference reference-800; do
  mkdir -p "$tmp/$ref"
  grep -E '^scene0[1-5]_' "$RAYFORM_SHARED/course/2019/$ref/MANIFEST.txt" > "$tmp/$ref/MANIFEST.txt"
  for f in "$RAYFORM_SHARED/course/2019/$ref"/scene0[1-5]_*.png; do ln -s "$f" "$tmp/$ref/"; done
  echo "== $ref"
  "$RAYFORM_SHARED/tools/course-parity" "$RAYFORM_BIN" "$RAYFORM_SHARED/course/2019" "$tmp/$ref" || status=1
done
exit $status
