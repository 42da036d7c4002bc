#!/usr/bin/env bash
# The nine 2012 course scenes converted to .glb and rendered directly by
# rayform (`render --color raw`, 200x200, colour and depth) against the
# course's reference pictures:
#  - as written by default (analytic spheres and planes, Phong materials, the
#    course camera and lights restored from the extras): the course-parity
#    rule, at most 0.5 % of pixels over 2/255;
#  - with --tessellate-only (spheres as 64-segment meshes, planes as quads,
#    which the reader does not turn back): within the tessellation error, at
#    most 2 % of pixels over 8/255.
source "$(dirname "$0")/lib.sh"
require_shared
c12=$RAYFORM_SHARED/course/2012
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
compare() {  # REF OUT FAIL_ABS FAIL_PERCENT LABEL
  local o rc pct
  o=$(idiff -fail "$3" -failpercent "$4" "$1" "$2" 2>&1); rc=$?
  pct=$(grep "over $3" <<<"$o" | sed -n 's/.*(\([0-9.]*\)%).*/\1/p')
  if [ $rc -le 1 ]; then printf '  %-32s PASS  %6s%% over %s\n' "$5" "${pct:-0}" "$3"
  else printf '  %-32s FAIL  %6s%% over %s (limit %s%%)\n' "$5" "${pct:-?}" "$3" "$4"; fail=1; fi
}
while read -r name size rest; do
  [ -n "$name" ] || continue
  read -r dmin dmax <<<"${rest##*depth }"
  W=${size%x*}; H=${size#*x}
  "$RAYFORM_BIN" convert "$c12/$name.txt" "$tmp/$name.glb" 2>/dev/null || { echo "FAIL: convert $name"; fail=1; continue; }
  "$RAYFORM_BIN" convert "$c12/$name.txt" "$tmp/${name}_tess.glb" --tessellate-only --sphere-segments 64 2>/dev/null ||
    { echo "FAIL: convert $name --tessellate-only"; fail=1; continue; }
  # The tessellated file must hold no analytic shape the reader could restore.
  if "$RAYFORM_BIN" info "$tmp/${name}_tess.glb" 2>/dev/null | grep -Eq '^(spheres|planes): +[1-9]'; then
    echo "FAIL: $name: --tessellate-only still holds analytic shapes"; fail=1
  fi
  echo "$name"
  for v in "" _tess; do
    "$RAYFORM_BIN" render "$tmp/$name$v.glb" -o "$tmp/c$v.png" --size "${W}x${H}" --color raw \
      --depth "$dmin:$dmax:$tmp/d$v.png" -q 2>"$tmp/log" || { echo "FAIL: render $name$v.glb: $(cat "$tmp/log")"; fail=1; continue; }
  done
  compare "$c12/reference/$name.png" "$tmp/c.png" 0.0079 0.5 "colour .glb"
  compare "$c12/reference/${name}_depth.png" "$tmp/d.png" 0.0079 0.5 "depth .glb"
  compare "$c12/reference/$name.png" "$tmp/c_tess.png" 0.0314 2 "colour .glb --tessellate-only"
  compare "$c12/reference/${name}_depth.png" "$tmp/d_tess.png" 0.0314 2 "depth .glb --tessellate-only"
done < "$c12/reference/MANIFEST.txt"
exit $fail
