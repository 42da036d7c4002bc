#!/usr/bin/env bash
# `rayform render` without --size: 512x512 for an asset (OBJ, glTF), the
# course's 200x200 for a course scene (default_render_options,
# pipeline/scene_ready.h); --size still wins. Before, every format got
# 200x200. Needs no third-party data.
source "$(dirname "$0")/lib.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
write_sphere_scene "$tmp/sphere.txt"

# check NAME INPUT WxH [flags]: renders INPUT to a PNG and compares its size.
check() {
  local name=$1 input=$2 want=$3 got
  shift 3
  if ! "$RAYFORM_BIN" render "$input" -o "$tmp/$name.png" -q "$@" >"$tmp/$name.log" 2>&1; then
    echo "FAIL $name: rayform failed: $(cat "$tmp/$name.log")"; fail=1; return
  fi
  got=$(oiiotool --info "$tmp/$name.png" | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1x\2/p')
  if [ "$got" = "$want" ]; then echo "PASS $name: $got"; else echo "FAIL $name: $got, expected $want"; fail=1; fi
}
check obj "$RAYFORM_SOURCE_DIR/scenes/assets/materials.obj" 512x512
check gltf "$RAYFORM_SOURCE_DIR/scenes/assets/features.glb" 512x512
check course "$tmp/sphere.txt" 200x200
check obj_sized "$RAYFORM_SOURCE_DIR/scenes/assets/materials.obj" 64x32 --size 64x32
exit $fail
