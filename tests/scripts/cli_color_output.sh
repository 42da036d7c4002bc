#!/usr/bin/env bash
# What `rayform render` writes for each kind of scene and file
# (src/render/color_output.h): an asset's float file (EXR) holds linear,
# unclamped values; its 8-bit file (PNG) the sRGB bytes of the same values;
# --color srgb encodes an EXR too; a course scene's EXR holds its raw values.
# The asset is a quad written here: Kd 0.5, Ke 2 1.5 0.25 (emission, so the
# linear colour is above 1), no camera and no light (the defaults: the
# framing camera looks at it head-on, the light rig gives a surface facing
# the camera 0.8434). Background: 0.5 (the asset formats' default).
# Pixels are read with oiiotool --dumpdata. Needs no third-party data.
# Before load_ready_scene and color_output.h, the asset's EXR held sRGB values
# clamped to 1 (centre 1 1 0.8808, background 0.7354) under a lone head-light.
source "$(dirname "$0")/lib.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }

cat >"$tmp/quad.mtl" <<'EOF'
newmtl glow
Kd 0.5 0.5 0.5
Ke 2 1.5 0.25
EOF
cat >"$tmp/quad.obj" <<'EOF'
mtllib quad.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vn 0 0 1
usemtl glow
f 1//1 2//1 3//1
f 1//1 3//1 4//1
EOF
write_sphere_scene "$tmp/sphere.txt"

# pixel FILE X Y: the pixel's channel values, space-separated.
pixel() { oiiotool --dumpdata "$1" | sed -n "s/^ *Pixel ($2, $3): //p"; }
# near "A B C ..." "X Y Z" TOL: every |A - X| <= TOL over the first three values.
near() {
  awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { n = split(a, x, " "); split(b, y, " "); if (n < 3) exit 1;
    for (i = 1; i <= 3; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > t) exit 1 } }'
}
run() { "$RAYFORM_BIN" render "$@" -q >"$tmp/log" 2>&1 || bad "rayform render $*: $(cat "$tmp/log")"; }

# The asset, 65x65: the centre pixel (32, 32) sees the quad head-on.
lit="2.4217 1.9217 0.6717"  # Ke + 0.5 * 0.8434
run "$tmp/quad.obj" -o "$tmp/q.exr" --size 65x65
c=$(pixel "$tmp/q.exr" 32 32) corner=$(pixel "$tmp/q.exr" 0 0)
near "$c" "$lit" 0.001 || bad "asset EXR: centre is '$c', expected linear $lit (above 1, not clamped)"
near "$corner" "0.5 0.5 0.5" 0 || bad "asset EXR: background is '$corner', expected linear 0.5 0.5 0.5"
echo "asset EXR: centre $c, background $corner"

run "$tmp/quad.obj" -o "$tmp/q.png" --size 65x65
c=$(pixel "$tmp/q.png" 32 32) corner=$(pixel "$tmp/q.png" 0 0)
# oiiotool prints an 8-bit file's bytes first: floor(255 sRGB(v)) of the same values, 255 where v >= 1,
# floor(255 sRGB(0.6717)) = 213; background floor(255 sRGB(0.5)) = 187.
near "$c" "255 255 213" 0 || bad "asset PNG: centre is '$c', expected bytes 255 255 213"
near "$corner" "187 187 187" 0 || bad "asset PNG: background is '$corner', expected sRGB bytes 187 187 187"
echo "asset PNG: centre $c, background $corner"

run "$tmp/quad.obj" -o "$tmp/s.exr" --size 65x65 --color srgb
corner=$(pixel "$tmp/s.exr" 0 0)
near "$corner" "0.735357 0.735357 0.735357" 0.00001 || bad "--color srgb EXR: background is '$corner', expected 0.735357"
echo "asset EXR, --color srgb: background $corner"

# A course scene: raw values (its background 0.1 0.2 0.3) in every file.
run "$tmp/sphere.txt" -o "$tmp/c.exr" --size 21x21
corner=$(pixel "$tmp/c.exr" 0 0)
near "$corner" "0.1 0.2 0.3" 0.000001 || bad "course EXR: background is '$corner', expected raw 0.1 0.2 0.3"
echo "course EXR: background $corner"

[ $fail -eq 0 ] && echo "PASS"
exit $fail
