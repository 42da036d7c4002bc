#!/usr/bin/env bash
# Golden test: the 2019 dialect's seven scenes (point-light falloff, raw up
# vector, cube-map background, -bounces reflections, -shadows) against its
# solution's pictures at 200x200 and at the course's own 800x800.
source "$(dirname "$0")/lib.sh"
require_shared
status=0
for ref in reference reference-800; do
  echo "== $ref"
  "$RAYFORM_SHARED/tools/course-parity" "$RAYFORM_BIN" "$RAYFORM_SHARED/course/2019" "$RAYFORM_SHARED/course/2019/$ref" || status=1
done
exit $status
