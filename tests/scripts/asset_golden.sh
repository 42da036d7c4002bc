#!/usr/bin/env bash
# Golden test of our own OBJ and glTF test assets (scenes/assets/materials.obj,
# features.gltf and features.glb, written by tests/tools/make_scene_assets.py):
# renders each row of tests/golden/assets/MANIFEST.txt (colour, depth, normals,
# albedo) with `rayform render` and compares with the committed pictures by
# the rule of own_scenes_golden.sh: at most 0.5 % of the pixels may differ by
# more than 2/255 (-fail 0.0079 -failpercent 0.5), all comparisons in one
# `oiiotool --diff` process. Needs no third-party data.
#
# With --update, (re)writes the golden pictures instead; look at them before
# committing.
source "$(dirname "$0")/lib.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
golden="$RAYFORM_SOURCE_DIR/tests/golden/assets"
update=0
[ "${1:-}" = "--update" ] && update=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

failn=0
compare=()  # oiiotool arguments: one --diff per picture
n=0
row=0
written=""
while read -r name input size depth flags; do
  case "$name" in ''|'#'*) continue ;; esac
  row=$((row + 1))
  out="$tmp/$row"; mkdir -p "$out"
  # shellcheck disable=SC2086  # flags is a word list
  if ! "$RAYFORM_BIN" render "$RAYFORM_SOURCE_DIR/$input" -o "$out/c.png" --size "$size" --depth "$depth:$out/d.png" \
       --normals "$out/n.png" --albedo "$out/a.png" -q $flags >"$out/log" 2>&1; then
    echo "FAIL $name ($input): rayform failed: $(cat "$out/log")"; failn=$((failn + 1)); continue
  fi
  for kind in c: d:_depth n:_normals a:_albedo; do
    k=${kind%%:*}; suffix=${kind#*:}
    ref="$golden/$name$suffix.png"
    if [ $update -eq 1 ]; then
      case " $written " in *" $name$suffix "*) continue ;; esac  # a repeated NAME keeps its first input's pictures
      written="$written $name$suffix"
      cp "$out/$k.png" "$ref"; echo "wrote $ref (from $input)"; continue
    fi
    if [ ! -f "$ref" ]; then echo "FAIL $name$suffix: no golden picture $ref"; failn=$((failn + 1)); continue; fi
    compare+=(--echo "== $name$suffix ($input)" "$ref" "$out/$k.png" --diff)
    n=$((n + 1))
  done
done <"$golden/MANIFEST.txt"
[ $update -eq 1 ] && exit $failn
compare_with_goldens "$n" "$failn" "$tmp"
