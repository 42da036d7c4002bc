#!/usr/bin/env bash
# BoxTextured (glTF sample model) as .gltf + .bin + .png, as .glb and as an
# embedded .gltf: rendered with the same camera (colour and albedo), the .glb
# and the embedded copy must be identical pixel for pixel.
#
# The .gltf copy is NOT expected to match them: its sampler is
# wrapS MIRRORED_REPEAT / wrapT CLAMP_TO_EDGE where the others use REPEAT, and
# its u coordinates run over [0, 6] (each face spans [k, k+1]), so the faces
# with odd k show the logo mirrored. This test checks instead that
#  1. the .gltf with its sampler patched to REPEAT/REPEAT renders exactly as
#     the .glb (the sampler is the files' only difference), and
#  2. the .gltf as it is (MIRRORED_REPEAT in u) renders as a copy whose
#     sampler is REPEAT in u and whose u coordinates are mirrored by hand on
#     the odd faces (u' = 2k + 1 - u), within 4/255 on all but 0.5 % of the pixels
#     (the interpolated u' differs from 2k + 1 - u by float rounding only).
source "$(dirname "$0")/lib.sh"
require_shared
g="$RAYFORM_SHARED/assets/gltf"
command -v python3 >/dev/null || { echo "FAIL: python3 not found"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# Copies of the .gltf folder: sampler REPEAT/REPEAT, and REPEAT in u with mirrored uvs.
mkdir -p "$tmp/repeat" "$tmp/mirrored"
cp "$g/BoxTextured-glTF/"* "$tmp/repeat/"
cp "$g/BoxTextured-glTF/"* "$tmp/mirrored/"
chmod u+w "$tmp/repeat/"* "$tmp/mirrored/"*
python3 - "$tmp" <<'EOF' || { echo "FAIL: could not patch the copies"; exit 1; }
import json, struct, sys, os
tmp = sys.argv[1]
for variant in ('repeat', 'mirrored'):
    path = os.path.join(tmp, variant, 'BoxTextured.gltf')
    d = json.load(open(path))
    assert d['samplers'][0]['wrapS'] == 33648 and d['samplers'][0]['wrapT'] == 33071, d['samplers']
    d['samplers'][0]['wrapS'] = 10497
    if variant == 'repeat':
        d['samplers'][0]['wrapT'] = 10497
    else:
        acc = d['accessors'][d['meshes'][0]['primitives'][0]['attributes']['TEXCOORD_0']]
        bv = d['bufferViews'][acc['bufferView']]
        binpath = os.path.join(tmp, variant, d['buffers'][bv['buffer']]['uri'])
        b = bytearray(open(binpath, 'rb').read())
        at = bv.get('byteOffset', 0) + acc.get('byteOffset', 0)
        stride = bv.get('byteStride', 8)
        uv = [list(struct.unpack_from('<2f', b, at + i * stride)) for i in range(acc['count'])]
        assert acc['count'] % 4 == 0
        odd = 0
        for face in range(acc['count'] // 4):  # four corners per face, u over [k, k+1]
            k = min(uv[4 * face + j][0] for j in range(4))
            assert k == int(k) and max(uv[4 * face + j][0] for j in range(4)) == k + 1
            if int(k) % 2 == 1:
                odd += 1
                for j in range(4):
                    uv[4 * face + j][0] = 2 * k + 1 - uv[4 * face + j][0]
        assert odd == 3, odd
        for i, (u, v) in enumerate(uv):
            struct.pack_into('<2f', b, at + i * stride, u, v)
        open(binpath, 'wb').write(bytes(b))
    json.dump(d, open(path, 'w'))
EOF

render() {  # NAME FILE
  if ! "$RAYFORM_BIN" render "$2" -o "$tmp/$1.png" --albedo "$tmp/$1_albedo.png" --size 200x200 \
       --look-from 1.2,1.0,1.6 --look-at 0,0,0 --up 0,1,0 --fov 45 -q >"$tmp/$1.log" 2>&1; then
    echo "FAIL: rayform failed on $2: $(cat "$tmp/$1.log")"; exit 1
  fi
}
render gltf "$g/BoxTextured-glTF/BoxTextured.gltf"
render glb "$g/BoxTextured-glTF-Binary/BoxTextured.glb"
render embedded "$g/BoxTextured-glTF-Embedded/BoxTextured.gltf"
render repeat "$tmp/repeat/BoxTextured.gltf"
render mirrored "$tmp/mirrored/BoxTextured.gltf"

failn=0
compare() {  # LABEL A B FAIL FAILPERCENT
  idiff -v -fail "$4" -failpercent "$5" -warn 1 "$tmp/$2.png" "$tmp/$3.png" >"$tmp/d.log" 2>&1; rc=$?
  over=$(sed -n "s/.*pixels (\(.*\)%) over $4\$/\1/p" "$tmp/d.log" | tail -1)
  max=$(sed -n 's/.*Max error  = \([^ ]*\).*/\1/p' "$tmp/d.log")
  if [ $rc -eq 0 ]; then
    echo "PASS $1: ${over:-0}% of pixels over $4 (limit $5%), max error ${max:-0}"
  else
    echo "FAIL $1: ${over:-?}% of pixels over $4 (limit $5%), max error ${max:-?}"; sed 's/^/    /' "$tmp/d.log"
    failn=$((failn + 1))
  fi
}
for k in "" _albedo; do
  name=${k:-_colour}; name=${name#_}
  compare "$name: .glb = embedded .gltf" "glb$k" "embedded$k" 0 0
  compare "$name: .gltf with REPEAT sampler = .glb" "repeat$k" "glb$k" 0 0
  compare "$name: .gltf (MIRRORED_REPEAT) ~ REPEAT with mirrored uvs" "gltf$k" "mirrored$k" 0.0157 0.5
  # For the record: how much the mirrored faces change the picture.
  idiff -v -fail 0.0157 "$tmp/gltf$k.png" "$tmp/glb$k.png" >"$tmp/d.log" 2>&1
  echo "info $name: .gltf vs .glb: $(sed -n 's/.*pixels (\(.*\)%) over 0.0157$/\1/p' "$tmp/d.log")% of pixels over 4/255 (expected: the mirrored faces)"
done
[ $failn -eq 0 ]
