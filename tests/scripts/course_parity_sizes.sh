#!/usr/bin/env bash
# Course parity at other, non-square sizes. The camera maps pixel i to
# x = 2i/(W-1) - 1 with one correctly rounded division, so at W = 399 the even
# column 2i has x = 4i/398 = 2i/199, exactly the x of column i at W = 200 (and
# likewise rows at H = 399). Rendering the 2012 scenes at 399x200, 200x399 and
# 399x399 and keeping the even columns/rows must therefore give:
#   1. our own 200x200 pictures exactly (colour, depth and normals), and
#   2. the reference 200x200 pictures by the course-parity rule (at most 0.5 %
#      of the pixels off by more than 2/255: -fail 0.0079 -failpercent 0.5).
# Decimation: oiiotool --resample:interp=0 200x200 takes pixel 2i of 399 (the
# new pixel centre (i + 0.5) * 399/200 lies in [2i, 2i + 1)); checked first.
source "$(dirname "$0")/lib.sh"
require_shared
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
course="$RAYFORM_SHARED/course/2012"
ref="$course/reference"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
decimate=(--resample:interp=0 200x200)

# 0. The decimation keeps exactly the even columns and rows: on a one-pixel
#    checkerboard (white where x + y is even) it must give all white.
if ! oiiotool --fail 0 --failpercent 0 --pattern constant:color=1,1,1 200x200 3 \
     --pattern checker:width=1:height=1:color1=1,1,1:color2=0,0,0 399x399 3 "${decimate[@]}" --diff >"$tmp/selfcheck" 2>&1; then
  echo "FAIL: oiiotool ${decimate[*]} does not keep the even pixels:"; cat "$tmp/selfcheck"; exit 1
fi

status=0
exact=()   # oiiotool arguments: own 200x200 vs decimated, exact
parity=()  # reference vs decimated, by the parity rule
n=0
while read -r name _ _ dmin dmax; do
  [ -n "$name" ] || continue
  out="$tmp/$name"; mkdir -p "$out"
  for s in 200x200 399x200 200x399 399x399; do
    W=${s%x*}; H=${s#*x}
    if ! (cd "$course" && "$RAYFORM_BIN" -input "$name.txt" -size "$W" "$H" -output "$out/c_$s.png" \
            -depth "$dmin" "$dmax" "$out/d_$s.png" -normals "$out/n_$s.png" -quiet) >"$out/log" 2>&1; then
      echo "FAIL $name $s: rayform failed: $(cat "$out/log")"; status=1; continue 2
    fi
  done
  for s in 399x200 200x399 399x399; do
    for kind in c: d:_depth n:_normals; do
      k=${kind%%:*}; suffix=${kind#*:}
      label="$name$suffix at $s"
      exact+=(--echo "== $label vs our 200x200" "$out/${k}_200x200.png" "$out/${k}_$s.png" "${decimate[@]}" --diff)
      parity+=(--echo "== $label vs reference" "$ref/$name$suffix.png" "$out/${k}_$s.png" "${decimate[@]}" --diff)
      n=$((n + 1))
    done
  done
done < "$ref/MANIFEST.txt"
[ $n -gt 0 ] || { echo "FAIL: no scenes in $ref/MANIFEST.txt"; exit 1; }

# Prints the label of every comparison that failed.
report() {
  awk '/^== /{label=substr($0, 4)} /FAILURE/{print "FAIL " label; bad=1} END{exit bad}' "$1"
}
oiiotool --fail 0 --failpercent 0 "${exact[@]}" >"$tmp/exact.log" 2>&1; rc_exact=$?
if ! report "$tmp/exact.log" || [ $rc_exact -ne 0 ]; then
  echo "even columns/rows differ from our own 200x200 pictures:"; cat "$tmp/exact.log"; status=1
else
  echo "exact: $n decimated pictures equal our own 200x200 renders"
fi
oiiotool --fail 0.0079 --failpercent 0.5 "${parity[@]}" >"$tmp/parity.log" 2>&1; rc_parity=$?
if ! report "$tmp/parity.log" || [ $rc_parity -ne 0 ]; then
  echo "decimated pictures fail course parity:"; cat "$tmp/parity.log"; status=1
else
  echo "parity: $n decimated pictures pass against the 2012 reference"
fi
exit $status
