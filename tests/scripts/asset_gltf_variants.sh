#!/usr/bin/env bash
# glTF files "as people download them": every model is re-written by the
# common npm tools into the forms found on model sites, and each form must
# render as the model it came from.
#
# Models: every .gltf/.glb and every .obj under $RAYFORM_SHARED/assets (an OBJ
# is first converted to .glb by obj2gltf 3.2.0, the peer tool; by `rayform
# convert` only when obj2gltf fails, and the line says so; OBJ files that
# convert to the same glTF but for names and paths, e.g. the obj2gltf edge
# cases about mtllib spellings, are run once: SKIP lines name the first), our own
# scenes/assets/features.gltf, and two generated scenes that repeat a mesh
# (tests/tools/make_instanced_gltf.py): the duck at 5 nodes, and 25
# icospheres at 25 nodes (whose other form is the same placements written by
# the generator itself with EXT_mesh_gpu_instancing).
#
# Variants (all written as .glb):
#   draco            gltf-transform draco                     KHR_draco_mesh_compression (edgebreaker)
#   draco-seq        gltf-transform draco --method sequential KHR_draco_mesh_compression
#   meshopt          gltf-transform meshopt                   EXT_meshopt_compression (+ KHR_mesh_quantization)
#   quantize         gltf-transform quantize                  KHR_mesh_quantization
#   webp             gltf-transform webp (lossy, default)     EXT_texture_webp; compared with the same file
#                    whose WebP images are decoded to PNG by `gltf-transform png --formats webp`
#                    (sharp/libwebp), since lossy WebP changes the texels themselves
#   webp-lossless    gltf-transform webp --lossless true      EXT_texture_webp
#   unweld           gltf-transform unweld                    (no extension: de-indexed geometry)
#   instance         gltf-transform instance                  EXT_mesh_gpu_instancing (a mesh used >= 5 times)
#   gltfpack         gltfpack -i IN -o OUT                    KHR_mesh_quantization (+ KHR_texture_transform)
#   gltfpack-cc      gltfpack -cc                             EXT_meshopt_compression
#   gltfpack-mi-cc   gltfpack -mi -cc                         EXT_mesh_gpu_instancing + EXT_meshopt_compression
# A variant whose tool fails, or does not produce its extension (webp on a
# model without textures, instance/-mi on a model that repeats no mesh, ...)
# is printed as SKIP and not counted.
#
# Comparison: the original and the variant are rendered at one explicit
# camera per model (framing the original's bounds from `rayform info`;
# quantizers move node transforms, not world positions), 256x256, depth
# (--depth NEAR:FAR around the bounds) and albedo pictures. A variant passes
# when, in both pictures (depth only for a model listed in albedo_unjudged,
# below), at most 2 % of the pixels differ by more than 6/255
# in any channel (idiff -fail 0.0236 -failpercent 2; run as oiiotool --fail
# 0.0236 --failpercent 2 ... --diff, the same comparison, all pictures of a
# model in one process, as lib.sh does). A variant rayform
# cannot load (or that crashes or times out) fails, with rayform's message.
# One line per variant "PASS|FAIL|SKIP MODEL VARIANT (why) [extensions used]",
# then "N passed, M failed"; exits non-zero when anything failed.
#
# Needs the node tools (scripts/install-node-tools: @gltf-transform/cli 4.5.1,
# gltfpack 1.3.0, obj2gltf 3.2.0), found in $RAYFORM_NODE_TOOLS, <build>/node
# or ~/.cache/rayform/node (installed there when npm can reach the registry);
# skipped (77) without them or without the third-party assets. The tool calls
# are made in few node processes (run_node_tools in lib.sh, through
# tests/tools/run_node_tools.mjs: the tools' own command code with the same
# arguments, byte-identical files): one for every OBJ -> .glb conversion, then
# the variants of all models in RAYFORM_GLTF_VARIANTS_JOBS processes at once,
# before the models are rendered and compared. A node start per call (about
# 1 s for gltf-transform and obj2gltf, 360 calls) was most of this test's
# time. A call those processes do not finish is made again with the tool's
# command.
# Environment: RAYFORM_GLTF_VARIANTS_MODELS / _VARIANTS (extended regular
# expressions: only the matching model names / variant names),
# RAYFORM_GLTF_VARIANTS_KEEP=DIR (keep every file and picture there),
# RAYFORM_GLTF_VARIANTS_JOBS (models in parallel, 1 or 2; default 2),
# RAYFORM_GLTF_VARIANTS_SIZE (default 256).
source "$(dirname "$0")/lib.sh"
assets=$RAYFORM_SHARED/assets
if [ ! -d "$assets" ]; then
  if [ -n "${CI:-}" ]; then echo "FAIL: third-party assets not found at $assets (required in CI)"; exit 1; fi
  echo "SKIPPED: third-party assets not found at $assets (set RAYFORM_SHARED)"; exit 77
fi
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool not found (apt-get install openimageio-tools)"; exit 1; }
command -v python3 >/dev/null || { echo "FAIL: python3 not found"; exit 1; }
find_node_tools node_modules/.bin/gltf-transform node_modules/.bin/gltfpack node_modules/.bin/obj2gltf
jobs=${RAYFORM_GLTF_VARIANTS_JOBS:-2}
[ "$jobs" -ge 1 ] 2>/dev/null && [ "$jobs" -le 2 ] || jobs=2
threads=$((2 / jobs))  # the machine budget: 2 cores in all
size=${RAYFORM_GLTF_VARIANTS_SIZE:-256}
export VIPS_CONCURRENCY=1 UV_THREADPOOL_SIZE=2  # sharp (webp/png) and node's pool: no more threads than cores
if [ -n "${RAYFORM_GLTF_VARIANTS_KEEP:-}" ]; then
  tmp=$RAYFORM_GLTF_VARIANTS_KEEP; mkdir -p "$tmp" || exit 1
else
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fi
# The tools' versions (one node process: run_node_tools, lib.sh).
mkdir -p "$tmp/versions"
printf '%s\t%s\t%s\t%s\n' "$tmp/versions" "$tmp/versions/gltf-transform" gltf-transform --version \
  "$tmp/versions" "$tmp/versions/gltfpack" gltfpack -v "$tmp/versions" "$tmp/versions/obj2gltf" obj2gltf --version \
  >"$tmp/versions/jobs"
run_node_tools "$tmp/versions/jobs" 60
echo "tools: gltf-transform $(tail -n 1 "$tmp/versions/gltf-transform")," \
     "$(head -n 1 "$tmp/versions/gltfpack"), obj2gltf $(cat "$tmp/versions/obj2gltf")"
gen="$RAYFORM_SOURCE_DIR/tests/tools/make_instanced_gltf.py"
py=$(python3 -c 'import sys; print(sys.executable)')  # the interpreter itself (a pyenv shim costs 0.2 s a call)
start=$SECONDS

# The extensions each .gltf/.glb uses: one line per file, "FILE<TAB>EXT,EXT"
# ("-" for none, "?" when unreadable). One python process for many files.
extensions() {
  "$py" - "$@" <<'EOF'
import json, struct, sys
for path in sys.argv[1:]:
    try:
        raw = open(path, 'rb').read()
        doc = json.loads(raw[20:20 + struct.unpack_from('<I', raw, 12)[0]] if raw[:4] == b'glTF' else raw)
        print(path + '\t' + (','.join(doc.get('extensionsUsed', [])) or '-'))
    except Exception:
        print(path + '\t?')
EOF
}

# name | tool | arguments (IN and OUT are substituted) | extension the variant must use ("" for none)
variants=(
  "draco|gltf-transform|draco IN OUT|KHR_draco_mesh_compression"
  "draco-seq|gltf-transform|draco --method sequential IN OUT|KHR_draco_mesh_compression"
  "meshopt|gltf-transform|meshopt IN OUT|EXT_meshopt_compression"
  "quantize|gltf-transform|quantize IN OUT|KHR_mesh_quantization"
  "webp|gltf-transform|webp IN OUT|EXT_texture_webp"
  "webp-lossless|gltf-transform|webp --lossless true IN OUT|EXT_texture_webp"
  "unweld|gltf-transform|unweld IN OUT|"
  "instance|gltf-transform|instance IN OUT|EXT_mesh_gpu_instancing"
  "gltfpack|gltfpack|-i IN -o OUT|KHR_mesh_quantization"
  "gltfpack-cc|gltfpack|-cc -i IN -o OUT|EXT_meshopt_compression"
  "gltfpack-mi-cc|gltfpack|-mi -cc -i IN -o OUT|EXT_mesh_gpu_instancing"
)

# Renders $1 into $2_depth.png and $2_albedo.png at the model's camera (the
# array `camera`, NEAR and FAR). On failure prints why and returns 1.
render() {
  local rc
  timeout 120 "$RAYFORM_BIN" render "$1" -o "$2_colour.png" --size "${size}x${size}" --threads "$threads" \
    "${camera[@]}" --depth "$near:$far:$2_depth.png" --albedo "$2_albedo.png" -q >"$2.log" 2>&1; rc=$?
  [ $rc -eq 0 ] && [ -s "$2_depth.png" ] && [ -s "$2_albedo.png" ] && return 0
  if [ $rc -eq 124 ]; then echo "rayform timed out after 120 s"
  elif [ $rc -gt 128 ]; then echo "rayform crashed (signal $((rc - 128))): $(tail -n 1 "$2.log" | cut -c1-200)"
  elif [ $rc -eq 0 ]; then echo "rayform wrote no depth or albedo picture"
  else echo "rayform failed: $( (grep -m 1 'error' "$2.log" || grep -v -m 1 -e '^note:' -e '^warning:' "$2.log") |
                              sed 's/^rayform: error: [^:]*: //' | cut -c1-240)"
  fi
  return 1
}

# Models whose albedo picture is not judged (reported only): which of their
# coincident faces a ray hits first is a tie that any change of vertex order or
# rounding may flip, so the albedo speckles between the faces' materials; or a
# texture so finely repeated that the variants' quantised uvs move it.
declare -A albedo_unjudged=(
  ["obj2gltf-edge-cases/box-mixed-attributes-2/box-mixed-attributes-2.obj"]="the cube is defined 4 times with different materials"
  ["khronos/SheenCloth/glTF/SheenCloth.gltf"]="its 256-texel weave repeats 30 times across the uv range (KHR_texture_transform scale 30), so uvs quantised to 12-16 bits (draco, meshopt, quantize, gltfpack) move it by up to a texel; the unquantised variants match exactly"
)

# The tool calls of a model's variants, queued in FOLDER/tools.jobs (for
# run_node_tools, lib.sh), and a SKIP reason in the caller's array `reason` for
# a variant whose tool has nothing to do, as FOLDER/info.txt (`rayform info`)
# shows: webp without textures, instancing where no mesh is used twice. The
# lossy WebP variant brings the call that decodes its WebP images to PNG (the
# reference of its comparison). Arguments: ORIGINAL FOLDER.
plan_variants() {
  local orig=$1 dir=$2 v vname tool args want out j textures instances meshes
  local -a argv
  textures=$(sed -n 's/^textures: *\([0-9]*\).*/\1/p' "$dir/info.txt")
  instances=$(sed -n 's/^instances: *\([0-9]*\).*/\1/p' "$dir/info.txt")
  meshes=$(sed -n 's/^triangles:.* in \([0-9]*\) meshes.*/\1/p' "$dir/info.txt")
  : >"$dir/tools.jobs"
  for v in "${variants[@]}"; do
    IFS='|' read -r vname tool args want <<<"$v"
    [[ $vname =~ ${RAYFORM_GLTF_VARIANTS_VARIANTS:-.} ]] || continue
    out="$dir/$vname.glb"
    if [ "$want" = EXT_texture_webp ] && [ "${textures:-0}" = 0 ]; then
      reason[$vname]="SKIP (no texture to convert)"
    elif [ "$want" = EXT_mesh_gpu_instancing ] && [ -n "$instances" ] && [ "$instances" = "$meshes" ]; then
      reason[$vname]="SKIP (no mesh used by several nodes: $instances placements of $meshes meshes)"
    else
      read -r -a argv <<<"$args"
      for j in "${!argv[@]}"; do
        case ${argv[j]} in IN) argv[j]=$orig ;; OUT) argv[j]=$out ;; esac
      done
      (IFS=$'\t'; echo "$dir"$'\t'"$dir/$vname.tool.log"$'\t'"$tool"$'\t'"${argv[*]}") >>"$dir/tools.jobs"
      [ "$vname" = webp ] && printf '%s\t' "$dir" "$dir/webp-png.tool.log" gltf-transform png --formats webp \
        "$dir/webp.glb" >>"$dir/tools.jobs" && echo "$dir/webp-png.glb" >>"$dir/tools.jobs"
    fi
  done
}

# One model: camera, every variant made
# and rendered, then all compared in one oiiotool process (idiff's rule and
# comparison, -fail 0.0236 -failpercent 2, without a process start per
# picture). Writes its result lines on stdout.
# Arguments: NAME ORIGINAL CONVERSION_NOTE FOLDER [PREMADE_NAME PREMADE_FILE].
do_model() {
  local name=$1 orig=$2 conv=$3 dir=$4 premade_name=${5:-} premade=${6:-}
  local line x0 y0 z0 x1 y1 z1 v vname tool args want out ref note why ext j kind status
  local -a made=() compare=() camera_nf
  local -A exts=() reason=() notes=() result=() share=() tool_status=()
  mkdir -p "$dir"

  # The camera: from the +x+y+z side, at the distance where the bounding
  # sphere just fills the 40 degree view; depth from the sphere's near to far side.
  "$RAYFORM_BIN" info "$orig" >"$dir/info.txt" 2>&1
  line=$(sed -n 's/^bounds: *(\(.*\)) - (\(.*\))$/\1, \2/p' "$dir/info.txt" | tr -d ',')
  read -r x0 y0 z0 x1 y1 z1 <<<"$line"
  if [ -z "${z1:-}" ]; then
    echo "FAIL $name original$conv (rayform info gives no bounds: $(tail -n 1 "$dir/info.txt" | cut -c1-200))"
    return
  fi
  read -r -a camera_nf < <(awk -v a="$x0" -v b="$y0" -v c="$z0" -v d="$x1" -v e="$y1" -v f="$z1" 'BEGIN {
    cx = (a + d) / 2; cy = (b + e) / 2; cz = (c + f) / 2
    r = sqrt((d - a) ^ 2 + (e - b) ^ 2 + (f - c) ^ 2) / 2; if (r <= 0) r = 1
    n = sqrt(0.55 ^ 2 + 0.45 ^ 2 + 0.70 ^ 2); dist = r / sin(20 * 3.14159265 / 180)
    printf "%.7g,%.7g,%.7g %.7g,%.7g,%.7g %.7g %.7g\n", cx + dist * 0.55 / n, cy + dist * 0.45 / n, cz + dist * 0.70 / n,
           cx, cy, cz, dist - 1.02 * r, dist + 1.02 * r }')
  # shellcheck disable=SC2054  # the commas are the options' own
  camera=(--look-from "${camera_nf[0]}" --look-at "${camera_nf[1]}" --up 0,1,0 --fov 40)
  near=${camera_nf[2]} far=${camera_nf[3]}
  if ! why=$(render "$orig" "$dir/original"); then
    echo "FAIL $name original$conv ($why) [$(extensions "$orig" | cut -f2)]"
    return
  fi

  # 1. The variants: those rayform info shows nothing to do for skipped, the
  #    others made by their tools (the calls of every model were made before,
  #    step 3 of the main part; here only when those have not been made).
  plan_variants "$orig" "$dir"
  if [ -s "$dir/tools.jobs" ]; then
    [ -f "$dir/tools.jobs.status" ] || run_node_tools "$dir/tools.jobs" 300
    while IFS=$'\t' read -r j out; do tool_status[$out]=$j; done <"$dir/tools.jobs.status"
  fi
  for v in "${variants[@]}" ${premade:+"$premade_name|premade||"}; do
    IFS='|' read -r vname tool args want <<<"$v"
    [[ $vname =~ ${RAYFORM_GLTF_VARIANTS_VARIANTS:-.} ]] || continue
    [ -z "${reason[$vname]:-}" ] || continue
    out="$dir/$vname.glb"
    if [ "$tool" = premade ]; then
      cp "$premade" "$out" || { reason[$vname]="SKIP (could not copy $premade)"; continue; }
    elif [ "${tool_status[$dir/$vname.tool.log]:-}" != 0 ] || [ ! -s "$out" ]; then
      reason[$vname]="SKIP ($tool could not make it: $( (grep -m 1 -i 'error' "$dir/$vname.tool.log" || tail -n 1 "$dir/$vname.tool.log") | cut -c1-160))"
      continue
    fi
    made+=("$vname")
  done

  # 2. Their extensions (one python process).
  if [ ${#made[@]} -gt 0 ]; then
    while IFS=$'\t' read -r out ext; do
      vname=${out%.glb}; exts[$vname]=$ext
    done < <(cd "$dir" && extensions "${made[@]/%/.glb}")
  fi

  # 3. Render them (and the PNG-decoded reference of the lossy WebP one); a
  #    variant without the extension its tool is for is skipped.
  compare=(--echo "== original stats" "$dir/original_depth.png" --printstats)
  for vname in "${made[@]}"; do
    want=""
    for v in "${variants[@]}"; do [ "${v%%|*}" = "$vname" ] && want=${v##*|}; done
    ext=${exts[$vname]:-?}
    if [ -n "$want" ] && [[ ",$ext," != *",$want,"* ]]; then
      case $want in
        EXT_texture_webp) why="no texture converted" ;;
        EXT_mesh_gpu_instancing) why="no mesh batched: none used by enough nodes" ;;
        *) why="the tool did not apply $want" ;;
      esac
      reason[$vname]="SKIP ($why) [$ext]"; continue
    fi
    ref="$dir/original" note=""
    if [ "$vname" = webp ]; then
      # lossy: the reference is this file with its WebP images decoded to PNG
      why=""
      if [ "${tool_status[$dir/webp-png.tool.log]:-}" != 0 ] || ! why=$(render "$dir/webp-png.glb" "$dir/webp-png"); then
        reason[$vname]="SKIP (could not make or render its PNG-decoded reference: $(tail -n 1 "$dir/webp-png.tool.log" | cut -c1-120) $why) [$ext]"
        continue
      fi
      ref="$dir/webp-png" note="; reference: its WebP images decoded to PNG"
    fi
    notes[$vname]=$note
    if ! why=$(render "$dir/$vname.glb" "$dir/$vname"); then
      reason[$vname]="FAIL ($why) [$ext]"; continue
    fi
    for kind in depth albedo; do
      compare+=(--echo "== $vname $kind" "${ref}_$kind.png" "$dir/${vname}_$kind.png" --diff)
    done
  done

  # 4. Compare everything queued, in one oiiotool process.
  oiiotool --fail 0.0236 --failpercent 2 "${compare[@]}" >"$dir/diff.log" 2>&1
  if grep -q '^ *Constant: Yes' "$dir/diff.log"; then
    echo "FAIL $name original$conv (its depth picture is uniform: nothing in view) [$(extensions "$orig" | cut -f2)]"
    return
  fi
  while read -r vname kind status p; do
    result[$vname $kind]=$status share[$vname $kind]=$p
  done < <(awk '/^== /{label = substr($0, 4); p[label] = "0"}
               /pixels \(.*%\) over 0.0236$/{s = $0; sub(/.*pixels \(/, "", s); sub(/%\).*/, "", s); p[label] = s}
               /^PASS/{st[label] = "PASS"} /^WARNING/{st[label] = "PASS"} /^FAILURE/{st[label] = "FAIL"}
               END {for (l in st) print l, st[l], p[l]}' "$dir/diff.log")

  # 5. One line per variant, in the table's order.
  for v in "${variants[@]}" ${premade:+"$premade_name|premade||"}; do
    vname=${v%%|*}
    [[ $vname =~ ${RAYFORM_GLTF_VARIANTS_VARIANTS:-.} ]] || continue
    if [ -n "${reason[$vname]:-}" ]; then
      echo "${reason[$vname]%% *} $name $vname$conv ${reason[$vname]#* }"; continue
    fi
    status=PASS why=""
    for kind in depth albedo; do
      if [ $kind = albedo ] && [ -n "${albedo_unjudged[$name]:-}" ] && [ -n "${result[$vname $kind]:-}" ]; then
        why+="${why:+, }albedo ${share[$vname $kind]}% (not judged)"; continue
      fi
      case ${result[$vname $kind]:-} in
        PASS) why+="${why:+, }$kind ${share[$vname $kind]}%" ;;
        FAIL) why+="${why:+, }$kind ${share[$vname $kind]}% (over the 2% limit)"; status=FAIL ;;
        *) why+="${why:+, }$kind not compared: $(grep -m 1 -i 'error' "$dir/diff.log" | cut -c1-160)"; status=FAIL ;;
      esac
    done
    [ -n "${albedo_unjudged[$name]:-}" ] && why+=" of pixels over 6/255; albedo not judged: ${albedo_unjudged[$name]}" ||
      why+=" of pixels over 6/255"
    echo "$status $name $vname$conv ($why${notes[$vname]:-}) [${exts[$vname]:-?}]"
  done
}

# The models: NAME|SOURCE[|PREMADE_NAME|PREMADE_FILE]
models=()
while IFS= read -r f; do
  models+=("${f#"$assets"/}|$f")
done < <(find "$assets" -type f \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.obj' \) | LC_ALL=C sort)
models+=("scenes/assets/features.gltf|$RAYFORM_SOURCE_DIR/scenes/assets/features.gltf")
mkdir -p "$tmp/generated"
if [ -f "$assets/duck/duck.gltf" ] &&
   "$py" "$gen" repeat "$assets/duck/duck.gltf" "$tmp/generated/duck-x5.glb" --count 5 >"$tmp/generated/duck.log" 2>&1; then
  models+=("generated/duck-x5.glb|$tmp/generated/duck-x5.glb")
else
  echo "FAIL: make_instanced_gltf.py repeat failed: $(tail -n 1 "$tmp/generated/duck.log")"; exit 1
fi
if "$py" "$gen" gpu "$tmp/generated/icospheres-x25-ext.glb" --count 25 --subdivisions 1 --spacing 4 \
     --nodes "$tmp/generated/icospheres-x25.glb" >"$tmp/generated/ico.log" 2>&1; then
  models+=("generated/icospheres-x25.glb|$tmp/generated/icospheres-x25.glb|ext-instancing(make_instanced_gltf.py)|$tmp/generated/icospheres-x25-ext.glb")
else
  echo "FAIL: make_instanced_gltf.py gpu failed: $(tail -n 1 "$tmp/generated/ico.log")"; exit 1
fi
selected=()
for m in "${models[@]}"; do
  [[ ${m%%|*} =~ ${RAYFORM_GLTF_VARIANTS_MODELS:-.} ]] && selected+=("$m")
done
[ ${#selected[@]} -gt 0 ] || { echo "FAIL: no model (RAYFORM_GLTF_VARIANTS_MODELS='${RAYFORM_GLTF_VARIANTS_MODELS:-}' matches none)"; exit 1; }

# 1. OBJ -> .glb (obj2gltf, every file in one node process: run_node_tools,
#    lib.sh; else rayform convert). Writes FOLDER/original.glb and FOLDER/conv
#    (the note for the result lines).
declare -A obj2gltf_status=()
convert_obj() {  # SOURCE FOLDER
  if [ "${obj2gltf_status[$2/obj2gltf.log]:-}" = 0 ] && [ -s "$2/original.glb" ]; then
    echo " (via obj2gltf)" >"$2/conv"
  elif timeout 120 "$RAYFORM_BIN" convert "$1" "$2/original.glb" >"$2/convert.log" 2>&1; then
    echo " (via rayform convert: obj2gltf failed: $( (grep -m 1 -i 'error' "$2/obj2gltf.log" || tail -n 1 "$2/obj2gltf.log") | cut -c1-100))" >"$2/conv"
  else
    rm -f "$2/original.glb"
    echo "obj2gltf and rayform convert both failed: $(tail -n 1 "$2/convert.log" | cut -c1-160)" >"$2/conv"
  fi
}
: >"$tmp/obj2gltf.jobs"
for ((k = 0; k < ${#selected[@]}; k++)); do
  IFS='|' read -r name src _ <<<"${selected[k]}"
  case $src in *.obj|*.OBJ) ;; *) continue ;; esac
  mkdir -p "$tmp/m$k"
  printf '%s\t' "$tmp/m$k" "$tmp/m$k/obj2gltf.log" obj2gltf -i "$src" -o >>"$tmp/obj2gltf.jobs"
  echo "$tmp/m$k/original.glb" >>"$tmp/obj2gltf.jobs"
done
if [ -s "$tmp/obj2gltf.jobs" ]; then
  run_node_tools "$tmp/obj2gltf.jobs" 120
  while IFS=$'\t' read -r status log; do obj2gltf_status[$log]=$status; done <"$tmp/obj2gltf.jobs.status"
fi
for ((k = 0; k < ${#selected[@]}; k++)); do
  IFS='|' read -r name src _ <<<"${selected[k]}"
  case $src in *.obj|*.OBJ) ;; *) continue ;; esac
  convert_obj "$src" "$tmp/m$k"
done

# 2. OBJ files that convert to the same glTF (but for names, paths and the
#    generator string) are the same test: only the first one is run.
"$py" - "$tmp" "${#selected[@]}" >"$tmp/duplicates.txt" <<'EOF'
import hashlib, json, os, struct, sys
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if k not in ('name', 'uri', 'generator')}
    return [strip(v) for v in o] if isinstance(o, list) else o
seen = {}
for k in range(int(sys.argv[2])):
    path = os.path.join(sys.argv[1], f'm{k}', 'original.glb')
    if not os.path.exists(path):
        continue
    raw = open(path, 'rb').read()
    n = struct.unpack_from('<I', raw, 12)[0]
    key = hashlib.sha256(json.dumps(strip(json.loads(raw[20:20 + n])), sort_keys=True).encode() + raw[20 + n:]).hexdigest()
    if key in seen:
        print(k, seen[key])
    else:
        seen[key] = k
EOF
declare -A duplicate_of=()
while read -r k first; do duplicate_of[$k]=$first; done <"$tmp/duplicates.txt"

# 3. The models to run (their original: FOLDER/original.glb for an OBJ).
declare -A original=() note=()
for ((k = 0; k < ${#selected[@]}; k++)); do
  IFS='|' read -r name src _ <<<"${selected[k]}"
  conv=""
  case $src in
    *.obj|*.OBJ)
      conv=$(cat "$tmp/m$k/conv")
      if [ ! -f "$tmp/m$k/original.glb" ]; then
        echo "SKIP $name * ($conv)" >"$tmp/result$k.txt"; continue
      elif [ -n "${duplicate_of[$k]:-}" ]; then
        echo "SKIP $name *$conv (the same glTF as ${selected[${duplicate_of[$k]}]%%|*} but for names and paths)" >"$tmp/result$k.txt"
        continue
      fi
      src=$tmp/m$k/original.glb ;;
  esac
  original[$k]=$src note[$k]=$conv
done

# 4. Every model's tool calls, made first in $jobs node processes (run_node_tools,
#    lib.sh; the models dealt to them in turn): a node process per model
#    would start gltf-transform (about 1 s) again and again.
lanes=0
rm -f "$tmp"/lane*.jobs*
for ((k = 0; k < ${#selected[@]}; k++)); do
  [ -n "${original[$k]:-}" ] || continue
  mkdir -p "$tmp/m$k"; rm -f "$tmp/m$k/tools.jobs.status"
  "$RAYFORM_BIN" info "${original[$k]}" >"$tmp/m$k/info.txt" 2>&1
  grep -q '^bounds:' "$tmp/m$k/info.txt" || continue  # do_model reports it
  declare -A reason=()
  plan_variants "${original[$k]}" "$tmp/m$k"
  unset reason
  cat "$tmp/m$k/tools.jobs" >>"$tmp/lane$((lanes % jobs)).jobs"
  lanes=$((lanes + 1))
done
for ((j = 0; j < jobs && j < lanes; j++)); do
  run_node_tools "$tmp/lane$j.jobs" 1200 300 &
done
wait
for ((j = 0; j < jobs && j < lanes; j++)); do
  while IFS=$'\t' read -r status log; do
    printf '%s\t%s\n' "$status" "$log" >>"${log%/*}/tools.jobs.status"
  done <"$tmp/lane$j.jobs.status"
done

# 5. The variants of every model rendered and compared, at most $jobs models at a time.
for ((k = 0; k < ${#selected[@]}; k++)); do
  [ -n "${original[$k]:-}" ] || continue
  IFS='|' read -r name _ pname pfile <<<"${selected[k]}"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
  do_model "$name" "${original[$k]}" "${note[$k]}" "$tmp/m$k" "$pname" "$pfile" >"$tmp/result$k.txt" 2>&1 &
done
wait
for ((k = 0; k < ${#selected[@]}; k++)); do cat "$tmp/result$k.txt"; done >"$tmp/results.txt"
cat "$tmp/results.txt"
passn=$(grep -c '^PASS' "$tmp/results.txt"); failn=$(grep -c '^FAIL' "$tmp/results.txt")
echo "(${#selected[@]} models, $(grep -c '^SKIP .* \* ' "$tmp/results.txt") of them skipped;" \
     "$(grep '^SKIP' "$tmp/results.txt" | grep -vc '^SKIP .* \* ') variants skipped; $((SECONDS - start)) s)"
echo "$passn passed, $failn failed"
[ "$failn" -eq 0 ] && [ "$passn" -gt 0 ]
