#!/usr/bin/env bash
# Golden test: the 2012 course scenes against the course solution's pictures
# (../shared/tools/course-parity; 2/255 on at most 0.5 % of pixels).
source "$(dirname "$0")/lib.sh"
require_shared
"$RAYFORM_SHARED/tools/course-parity" "$RAYFORM_BIN" "$RAYFORM_SHARED/course/2012" "$RAYFORM_SHARED/course/2012/reference"
