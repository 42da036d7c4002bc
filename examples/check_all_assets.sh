#!/usr/bin/env bash
# Test of examples/render_scene.cpp over every OBJ and glTF (.gltf, .glb) file
# under $RAYFORM_SHARED/assets: each, rendered with the example's defaults
# (512x512, the default camera and light rig where the file has none), must
# give a non-empty, lit picture:
#   covered  the share of pixels whose colour differs from the background
#            (the corner pixel: the framing camera leaves a 10 % margin) by
#            more than 2/255 in some channel: at least 1 %;
#   lit      the mean over those pixels of (R + G + B) / 3, sRGB bytes: at
#            least 20. Measured: 33.3 (the spider, dark textures) to 214.0
#            over the 59 files rendered (covered: 7.4 % to 82.1 %); an unlit
#            model (before the light rig: the duck in black) is near 0.
# A file the example cannot render fails, unless `rayform render` refuses it
# too: it is then listed as skipped, with the CLI's error. A file listed in
# `known` below fails for a reason an open issue names: it is reported, and
# fails the test only once it passes (then take it off the list).
# Environment: EXAMPLE (the example's binary), RAYFORM_BIN, RAYFORM_SHARED.
set -uo pipefail
: "${EXAMPLE:?EXAMPLE must name rayform_example_render}"
: "${RAYFORM_BIN:?RAYFORM_BIN must name the rayform binary}"
shared=${RAYFORM_SHARED:-}
if [ -z "$shared" ] || [ ! -d "$shared/assets" ]; then
  if [ -n "${CI:-}" ]; then echo "FAIL: third-party data not found at '$shared' (required in CI)"; exit 1; fi
  echo "SKIPPED: third-party data not found at '$shared' (set RAYFORM_SHARED)"; exit 77
fi
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
command -v python3 >/dev/null || { echo "FAIL: python3 not found"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

min_covered=1 min_lit=20
# Known failures, each with its reason and the issue that will fix it.
# (None at present: TwoSidedPlane, seen edge-on before issue 30, is framed from above.)
declare -A known=()
n=0 failn=0 skipn=0 knownn=0
while IFS= read -r -d '' file; do
  n=$((n + 1))
  rel=${file#"$shared"/}
  if ! "$EXAMPLE" "$file" "$tmp/out.png" >"$tmp/log" 2>&1; then
    if ! "$RAYFORM_BIN" render "$file" -o "$tmp/cli.png" -q >"$tmp/cli.log" 2>&1; then
      echo "SKIP $rel: the CLI refuses it too: $(head -n 1 "$tmp/cli.log")"; skipn=$((skipn + 1)); continue
    fi
    echo "FAIL $rel: the example failed: $(grep -m 1 error "$tmp/log")"; failn=$((failn + 1)); continue
  fi
  oiiotool "$tmp/out.png" -o "$tmp/out.ppm" || { echo "FAIL $rel: cannot convert the picture"; failn=$((failn + 1)); continue; }
  # Prints: WIDTH HEIGHT COVERED_PERCENT LIT_MEAN
  read -r w h covered lit < <(python3 - "$tmp/out.ppm" <<'EOF'
import sys
data = open(sys.argv[1], "rb").read()
fields, pos = [], 0
while len(fields) < 4:  # P6 header: magic, width, height, maxval, then one whitespace byte
    while data[pos:pos + 1].isspace(): pos += 1
    start = pos
    while not data[pos:pos + 1].isspace(): pos += 1
    fields.append(data[start:pos])
w, h = int(fields[1]), int(fields[2])
px = data[pos + 1:pos + 1 + 3 * w * h]
bg = px[0:3]
covered, total = 0, 0
for i in range(0, len(px), 3):
    r, g, b = px[i], px[i + 1], px[i + 2]
    if abs(r - bg[0]) > 2 or abs(g - bg[1]) > 2 or abs(b - bg[2]) > 2:
        covered += 1
        total += r + g + b
print(w, h, "%.2f" % (100.0 * covered / (w * h)), "%.1f" % (total / 3.0 / covered if covered else 0.0))
EOF
)
  line="$rel: ${w}x${h}, covered ${covered} %, lit mean ${lit}"
  if [ "$w" != 512 ] || [ "$h" != 512 ] ||
     ! awk -v c="$covered" -v l="$lit" -v mc=$min_covered -v ml=$min_lit 'BEGIN { exit !(c >= mc && l >= ml) }'; then
    if [ -n "${known[$rel]:-}" ]; then
      echo "KNOWN $line: ${known[$rel]}"; knownn=$((knownn + 1))
    else
      echo "FAIL $line (want 512x512, covered >= $min_covered %, lit mean >= $min_lit)"; failn=$((failn + 1))
    fi
  elif [ -n "${known[$rel]:-}" ]; then
    echo "FAIL $line: listed as a known failure (${known[$rel]}) but passes: take it off the list"; failn=$((failn + 1))
  else
    echo "PASS $line"
  fi
done < <(find "$shared/assets" -type f \( -iname '*.obj' -o -iname '*.gltf' -o -iname '*.glb' \) -print0 | sort -z)

echo "$((n - failn - skipn - knownn)) of $n files give a lit picture, $skipn skipped (refused by the CLI too), $knownn known failures, $failn failed"
[ "$n" -gt 0 ] && [ $failn -eq 0 ]
