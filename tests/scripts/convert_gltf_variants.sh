#!/usr/bin/env bash
# `rayform convert` of glTF files as people download them (Draco, meshopt,
# quantised, lossless WebP, GPU-instanced) writes plain files: every .glb/.gltf passes
# the Khronos validator with 0 errors; the written .glb and .gltf render like
# the variant they came from, and the written .obj and course .txt like the
# same conversion of the plain original (those formats cannot hold
# everything glTF can, e.g. texture repeat or single-sided materials, and
# convert reports such losses; what is checked here is that the variant adds
# none). Pictures: one explicit camera per model, framing its bounds from
# `rayform info`, 128x128; albedo, and normals where the format's normals
# picture has glTF's convention (not the course's); at most 2 % of pixels
# over 6/255, the asset_gltf_variants.sh rule.
# Models: the duck, BoxTextured (.glb), TextureTransformTest (repeats a
# mesh: gltfpack -mi instances it) and our scenes/assets/features.gltf.
# Skips (77) without node, the node tools or the third-party assets.
source "$(dirname "$0")/lib.sh"
require_shared
find_node_tools node_modules/.bin/gltf-transform node_modules/.bin/gltfpack node_modules/gltf-validator/package.json
tools=$RAYFORM_NODE_TOOLS
bin=$tools/node_modules/.bin
export VIPS_CONCURRENCY=1 UV_THREADPOOL_SIZE=2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
a=$RAYFORM_SHARED/assets
models=("$a/duck/duck.gltf" "$a/gltf/BoxTextured-glTF-Binary/BoxTextured.glb"
        "$a/gltf/textureTransform/TextureTransformTest.gltf" "$RAYFORM_SOURCE_DIR/scenes/assets/features.gltf")
fail=0; passed=0; failed=0
camera=()
render() {  # IN PREFIX: PREFIX_normals.png, PREFIX_albedo.png at the model's camera
  "$RAYFORM_BIN" render "$1" -o "$2.png" --size 128x128 --normals "$2_normals.png" --albedo "$2_albedo.png" \
    "${camera[@]}" --threads 2 -q >/dev/null 2>"$tmp/render.log"
}
for m in "${models[@]}"; do
  name=$(basename "$m"); name=${name%.*}
  # A camera on the diagonal of the bounds, looking at their centre.
  read -r -a camera < <("$RAYFORM_BIN" info "$m" 2>/dev/null | awk -F'[(), ]+' '/^bounds:/ {
    cx = ($2 + $5) / 2; cy = ($3 + $6) / 2; cz = ($4 + $7) / 2
    r = sqrt(($5 - $2) ^ 2 + ($6 - $3) ^ 2 + ($7 - $4) ^ 2) / 2
    printf "--look-from %g,%g,%g --look-at %g,%g,%g --up 0,1,0 --fov 45", cx + 1.4 * r, cy + 1.1 * r, cz + 1.9 * r, cx, cy, cz }')
  for ext in obj txt; do  # the plain original's conversions: the references for .obj and .txt
    mkdir -p "$tmp/ref_${name}_$ext"
    if ! "$RAYFORM_BIN" convert "$m" "$tmp/ref_${name}_$ext/model.$ext" >/dev/null 2>&1 ||
       ! render "$tmp/ref_${name}_$ext/model.$ext" "$tmp/ref_${name}_$ext/r"; then
      echo "FAIL $name -> .$ext: the plain original does not convert and render"; failed=$((failed + 1))
    fi
  done
  variants=()
  "$bin/gltf-transform" draco "$m" "$tmp/${name}_draco.glb" >/dev/null 2>&1 && variants+=(draco)
  "$bin/gltf-transform" meshopt "$m" "$tmp/${name}_meshopt.glb" >/dev/null 2>&1 && variants+=(meshopt)
  "$bin/gltfpack" -cc -i "$m" -o "$tmp/${name}_gltfpack-cc.glb" >/dev/null 2>&1 && variants+=(gltfpack-cc)
  "$bin/gltfpack" -mi -cc -i "$m" -o "$tmp/${name}_gltfpack-mi.glb" >/dev/null 2>&1 && variants+=(gltfpack-mi)
  grep -q '"images"' "$m" 2>/dev/null || [[ $m == *.glb ]] &&
    "$bin/gltf-transform" webp --lossless true "$m" "$tmp/${name}_webp.glb" >/dev/null 2>&1 && variants+=(webp)
  for v in "${variants[@]}"; do
    src="$tmp/${name}_$v.glb"; out="$tmp/out_${name}_$v"
    if ! render "$src" "$out-src"; then
      echo "FAIL $name $v: the variant does not render: $(tail -c 300 "$tmp/render.log")"; failed=$((failed + 1)); continue
    fi
    for ext in glb gltf obj txt; do
      # WebP (lossless too) does not keep the colour under fully transparent
      # texels; OBJ and the course format have no cut-outs and show it.
      if [ "$v" = webp ] && [ "$name" = features ] && { [ $ext = obj ] || [ $ext = txt ]; }; then
        echo "SKIP $name $v -> .$ext (cut-out texture: WebP drops the colour under its holes, which .$ext shows)"
        continue
      fi
      mkdir -p "$out-$ext"
      if ! "$RAYFORM_BIN" convert "$src" "$out-$ext/model.$ext" >/dev/null 2>"$tmp/convert.log"; then
        echo "FAIL $name $v -> .$ext: $(tail -c 300 "$tmp/convert.log")"; failed=$((failed + 1)); continue
      fi
      if ! render "$out-$ext/model.$ext" "$out-$ext/r"; then
        echo "FAIL $name $v -> .$ext: the converted file does not render: $(tail -c 300 "$tmp/render.log")"
        failed=$((failed + 1)); continue
      fi
      ok=1
      pics=(albedo); [ $ext = txt ] || pics+=(normals)
      ref=$out-src; [ $ext = obj ] || [ $ext = txt ] && ref=$tmp/ref_${name}_$ext/r
      for pic in "${pics[@]}"; do
        oiiotool --fail 0.0236 --failpercent 2 "${ref}_$pic.png" "$out-$ext/r_$pic.png" --diff >"$tmp/diff.log" 2>&1 ||
          { ok=0; echo "FAIL $name $v -> .$ext: $pic differs: $(grep -E 'pixels|Max' "$tmp/diff.log" | tr '\n' ' ')"; }
      done
      if [ $ok = 1 ]; then passed=$((passed + 1)); echo "PASS $name $v -> .$ext"; else failed=$((failed + 1)); fi
    done
  done
done
written=("$tmp"/out_*-glb/model.glb "$tmp"/out_*-gltf/model.gltf)
node "$RAYFORM_SOURCE_DIR/tests/tools/validate_gltf.js" "${written[@]}" >"$tmp/report" 2>&1
errors=$(grep -vc "errors 0," "$tmp/report" || true)
grep -v "errors 0," "$tmp/report" | head -20
clean=$(grep -c "errors 0," "$tmp/report")
echo "validator: $clean of ${#written[@]} converted glTF files with 0 errors"
[ "$clean" -eq "${#written[@]}" ] || { fail=1; failed=$((failed + 1)); }
[ "$errors" -eq 0 ] || fail=1
echo "$passed passed, $failed failed"
[ $fail = 0 ] && [ $failed = 0 ]
