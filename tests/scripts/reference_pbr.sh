#!/usr/bin/env bash
# rayform's pictures of glTF samples under an HDR environment against the
# path-traced references of $RAYFORM_SHARED/reference-pbr (Blender 3.4
# Cycles, the `direct` variant: environment light with shadows, glossy and
# transmission paths, no diffuse interreflection; see its NOTES.md).
#
# For each row of reference-pbr/MANIFEST.tsv (model, camera in glTF
# coordinates, size, environment) it renders
#   rayform render MODEL -o OUT.exr --env ENV --look-from EYE --look-at TARGET
#     --up UP --fov FOV --size WxH --spp SPP --tonemap none
# and compares the sRGB encodings (clamped to 0..1, oiiotool --tocolorspace
# sRGB) of OUT.exr and the reference EXR: the mean absolute difference over
# the image, and over the model's pixels (the mask EXR's alpha as weight).
# Limits (issue 31): the means over the rows run, image <= 0.02 and model
# <= 0.03; no row over 0.05 (image or model). One line per row:
# "PASS|FAIL MODEL ENV image X model Y (SECONDS s)", then the means.
#
# Environment: RAYFORM_REFERENCE_MODELS (an extended regular expression on
# the model names; default: Avocado, which CI runs), RAYFORM_REFERENCE_SPP
# (default 256), RAYFORM_REFERENCE_KEEP=DIR (keep the pictures there).
source "$(dirname "$0")/lib.sh"
ref=$RAYFORM_SHARED/reference-pbr
if [ ! -f "$ref/MANIFEST.tsv" ]; then
  if [ -n "${CI:-}" ]; then echo "FAIL: $ref/MANIFEST.tsv not found (required in CI)"; exit 1; fi
  echo "SKIPPED: $ref/MANIFEST.tsv not found (set RAYFORM_SHARED)"; exit 77
fi
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
models=${RAYFORM_REFERENCE_MODELS:-^Avocado$}
spp=${RAYFORM_REFERENCE_SPP:-256}
if [ -n "${RAYFORM_REFERENCE_KEEP:-}" ]; then
  tmp=$RAYFORM_REFERENCE_KEEP; mkdir -p "$tmp" || exit 1
else
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fi

n=0 failn=0 image_sum=0 model_sum=0
while IFS=$'\t' read -r model file eye target up fov size env variant samples seconds exr png mask; do
  [ "$model" = model ] && continue
  [[ $model =~ $models ]] || continue
  [ "$variant" = direct ] || continue
  n=$((n + 1))
  name="${model}__$(basename "$env" .exr)"
  out="$tmp/$name.exr"
  start=$SECONDS
  if ! "$RAYFORM_BIN" render "$RAYFORM_SHARED/assets/khronos/$file" -o "$out" --env "$ref/$env" \
       --look-from "$eye" --look-at "$target" --up "$up" --fov "$fov" --size "$size" --spp "$spp" \
       --tonemap none -q >"$tmp/$name.log" 2>&1; then
    echo "FAIL $model $(basename "$env" .exr): rayform failed: $(head -c 300 "$tmp/$name.log")"; failn=$((failn + 1))
    continue
  fi
  took=$((SECONDS - start))
  read -r image model_error < <(reference_errors "$out" "$ref/$exr" "$ref/$mask" "$tmp/$name.diff.exr") ||
    { echo "FAIL $model $(basename "$env" .exr): comparison failed"; failn=$((failn + 1)); continue; }
  verdict=$(awk -v i="$image" -v m="$model_error" 'BEGIN {
    printf "%s image %.4f model %.4f", i <= 0.05 && m <= 0.05 ? "PASS" : "FAIL", i, m }')
  echo "${verdict%% *} $model $(basename "$env" .exr) ${verdict#* } (${took} s)"
  [ "${verdict%% *}" = PASS ] || failn=$((failn + 1))
  image_sum=$(awk -v a="$image_sum" -v b="$image" 'BEGIN { print a + b }')
  model_sum=$(awk -v a="$model_sum" -v b="$model_error" 'BEGIN { print a + b }')
done <"$ref/MANIFEST.tsv"
[ "$n" -gt 0 ] || { echo "FAIL: no MANIFEST row matched '$models'"; exit 1; }
means=$(awk -v i="$image_sum" -v m="$model_sum" -v n="$n" 'BEGIN {
  printf "%s: mean image %.4f (limit 0.02), mean model %.4f (limit 0.03)",
    i / n <= 0.02 && m / n <= 0.03 ? "PASS" : "FAIL", i / n, m / n }')
echo "${means}; $((n - failn)) of $n pictures under 0.05"
[ "$failn" -eq 0 ] && [ "${means%%:*}" = PASS ]
