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
# Variants: gltf-transform draco, meshopt, webp --lossless true (models with
# images); gltfpack -cc, -mi -cc; a variant whose tool fails is left out.
# All the tool calls are made in one node process first (run_node_tools in
# lib.sh, tests/tools/run_node_tools.mjs: the tools' own command code, the
# same files), and a model's pictures are compared in one oiiotool process:
# a node start (about 1 s) per tool call and an oiiotool start (0.3 s) per
# picture were most of this test's time.
# Skips (77) without node, the node tools or the third-party assets.
source "$(dirname "$0")/lib.sh"
require_shared
find_node_tools node_modules/.bin/gltf-transform node_modules/.bin/gltfpack node_modules/gltf-validator/package.json
export VIPS_CONCURRENCY=1 UV_THREADPOOL_SIZE=2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
a=$RAYFORM_SHARED/assets
models=("$a/duck/duck.gltf" "$a/gltf/BoxTextured-glTF-Binary/BoxTextured.glb"
        "$a/gltf/textureTransform/TextureTransformTest.gltf" "$RAYFORM_SOURCE_DIR/scenes/assets/features.gltf")
fail=0; passed=0; failed=0
camera=()
declare -A verdict=() details=()

# The variants of every model, made in one node process (run_node_tools,
# lib.sh): NAME, TOOL and its arguments (IN and OUT substituted); webp only for
# a model with images (or a .glb, which may hold them).
variants=("draco|gltf-transform|draco IN OUT" "meshopt|gltf-transform|meshopt IN OUT"
          "gltfpack-cc|gltfpack|-cc -i IN -o OUT" "gltfpack-mi|gltfpack|-mi -cc -i IN -o OUT"
          "webp|gltf-transform|webp --lossless true IN OUT")
: >"$tmp/tools.jobs"
for m in "${models[@]}"; do
  name=$(basename "$m"); name=${name%.*}
  for v in "${variants[@]}"; do
    IFS='|' read -r vname tool args <<<"$v"
    if [ "$vname" = webp ] && ! { grep -q '"images"' "$m" 2>/dev/null || [[ $m == *.glb ]]; }; then continue; fi
    read -r -a argv <<<"$args"
    for j in "${!argv[@]}"; do
      case ${argv[j]} in IN) argv[j]=$m ;; OUT) argv[j]=$tmp/${name}_$vname.glb ;; esac
    done
    (IFS=$'\t'; echo "$tmp"$'\t'"$tmp/${name}_$vname.log"$'\t'"$tool"$'\t'"${argv[*]}") >>"$tmp/tools.jobs"
  done
done
run_node_tools "$tmp/tools.jobs" 300
declare -A tool_status=()
while IFS=$'\t' read -r status log; do tool_status[$log]=$status; done <"$tmp/tools.jobs.status"

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
  made=()
  for v in "${variants[@]}"; do
    v=${v%%|*}
    [ "${tool_status[$tmp/${name}_$v.log]:-}" = 0 ] && made+=("$v")
  done
  # The model's result lines, in order; a line "?LABEL" stands for the
  # comparisons queued under LABEL (one oiiotool process per model, below).
  lines=(); compare=()
  for v in "${made[@]}"; do
    src="$tmp/${name}_$v.glb"; out="$tmp/out_${name}_$v"
    if ! render "$src" "$out-src"; then
      lines+=("FAIL $name $v: the variant does not render: $(tail -c 300 "$tmp/render.log")"); failed=$((failed + 1)); continue
    fi
    for ext in glb gltf obj txt; do
      # WebP (lossless too) does not keep the colour under fully transparent
      # texels; OBJ and the course format have no cut-outs and show it.
      if [ "$v" = webp ] && [ "$name" = features ] && { [ $ext = obj ] || [ $ext = txt ]; }; then
        lines+=("SKIP $name $v -> .$ext (cut-out texture: WebP drops the colour under its holes, which .$ext shows)")
        continue
      fi
      mkdir -p "$out-$ext"
      if ! "$RAYFORM_BIN" convert "$src" "$out-$ext/model.$ext" >/dev/null 2>"$tmp/convert.log"; then
        lines+=("FAIL $name $v -> .$ext: $(tail -c 300 "$tmp/convert.log")"); failed=$((failed + 1)); continue
      fi
      if ! render "$out-$ext/model.$ext" "$out-$ext/r"; then
        lines+=("FAIL $name $v -> .$ext: the converted file does not render: $(tail -c 300 "$tmp/render.log")")
        failed=$((failed + 1)); continue
      fi
      pics=(albedo); [ $ext = txt ] || pics+=(normals)
      ref=$out-src; [ $ext = obj ] || [ $ext = txt ] && ref=$tmp/ref_${name}_$ext/r
      for pic in "${pics[@]}"; do
        compare+=(--echo "== $name $v -> .$ext $pic" "${ref}_$pic.png" "$out-$ext/r_$pic.png" --diff)
      done
      lines+=("?$name $v -> .$ext|${pics[*]}")
    done
  done
  # The model's comparisons in one oiiotool process (idiff's rule: at most 2 %
  # of the pixels over 6/255); per comparison its verdict and its lines.
  verdict=(); details=()
  if [ ${#compare[@]} -gt 0 ]; then
    oiiotool --fail 0.0236 --failpercent 2 "${compare[@]}" >"$tmp/diff.log" 2>&1
    label=""
    while IFS= read -r line; do
      case $line in
        "== "*) label=${line#== }; continue ;;
        PASS*|WARNING*) verdict[$label]=pass ;;
        FAILURE*) verdict[$label]=fail ;;
      esac
      [[ $line =~ pixels|Max ]] && details[$label]+="$line "
    done <"$tmp/diff.log"
  fi
  for line in "${lines[@]}"; do
    if [ "${line:0:1}" != "?" ]; then echo "$line"; continue; fi
    label=${line:1}; label=${label%|*}; ok=1
    for pic in ${line##*|}; do
      v=${verdict[$label $pic]:-}
      if [ -z "$v" ]; then  # not compared: oiiotool stopped early (an unreadable picture); alone, as before
        for ((j = 0; j < ${#compare[@]}; j++)); do
          if [ "${compare[j]}" = "== $label $pic" ]; then
            oiiotool --fail 0.0236 --failpercent 2 "${compare[j + 1]}" "${compare[j + 2]}" --diff >"$tmp/diff1.log" 2>&1 && v=pass || v=fail
            details[$label $pic]=$(grep -E 'pixels|Max' "$tmp/diff1.log" | tr '\n' ' ')
          fi
        done
      fi
      [ "$v" = pass ] || { ok=0; echo "FAIL $label: $pic differs: ${details[$label $pic]:-}"; }
    done
    if [ $ok = 1 ]; then passed=$((passed + 1)); echo "PASS $label"; else failed=$((failed + 1)); fi
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
