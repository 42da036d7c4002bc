#!/usr/bin/env bash
# Golden test of our own scenes (scenes/default.txt, scenes/tests/*.txt):
# renders each scene of tests/golden/MANIFEST.txt (colour, depth, normals)
# and compares with the committed pictures by the course-parity rule: at most
# 0.5 % of the pixels may differ by more than 2/255 (-fail 0.0079
# -failpercent 0.5). The comparisons are idiff's, run as `oiiotool --diff` in
# a single process (each idiff start costs ~0.5 s). Needs no third-party data.
#
# With --update, (re)writes the golden pictures instead; look at them before
# committing.
source "$(dirname "$0")/lib.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
golden="$RAYFORM_SOURCE_DIR/tests/golden"
update=0
[ "${1:-}" = "--update" ] && update=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

failn=0
compare=()  # oiiotool arguments: one --diff per picture
n=0
while read -r name scene size dmin dmax flags; do
  case "$name" in ''|'#'*) continue ;; esac
  W=${size%x*}; H=${size#*x}
  out="$tmp/$name"; mkdir -p "$out"
  # shellcheck disable=SC2086  # flags is a word list
  if ! "$RAYFORM_BIN" -input "$RAYFORM_SOURCE_DIR/$scene" -size "$W" "$H" -output "$out/c.png" \
       -depth "$dmin" "$dmax" "$out/d.png" -normals "$out/n.png" -quiet $flags >"$out/log" 2>&1; then
    echo "FAIL $name: rayform failed: $(cat "$out/log")"; failn=$((failn + 1)); continue
  fi
  for kind in c: d:_depth n:_normals; do
    k=${kind%%:*}; suffix=${kind#*:}
    ref="$golden/$name$suffix.png"
    if [ $update -eq 1 ]; then
      cp "$out/$k.png" "$ref"; echo "wrote $ref"; continue
    fi
    if [ ! -f "$ref" ]; then echo "FAIL $name$suffix: no golden picture $ref"; failn=$((failn + 1)); continue; fi
    compare+=(--echo "== $name$suffix" "$ref" "$out/$k.png" --diff)
    n=$((n + 1))
  done
done <"$golden/MANIFEST.txt"
[ $update -eq 1 ] && exit 0
compare_with_goldens "$n" "$failn" "$tmp"
