#!/usr/bin/env bash
# The duck as OBJ (+MTL) and as glTF (same model, exported twice) is the same
# model through the one shader: with the same explicit camera and size, the
# depth, normals and albedo pictures may differ by more than 4/255 (in any
# channel) in at most 1 % of the pixels (idiff -fail 0.0157 -failpercent 1).
# Prints the measured share of such pixels per picture. The colour pictures
# are compared for the report only: the OBJ's material is the course's Phong
# model (Kd/Ks/Ns; Ks 0.5 with Ns 0, which the OBJ reader reads as no
# highlight) and the glTF's the metallic-roughness model (a rough dielectric,
# tone mapped by default), both lit by the light rig along the camera.
source "$(dirname "$0")/lib.sh"
require_shared
duck="$RAYFORM_SHARED/assets/duck"
if [ ! -f "$duck/duck.obj" ] || [ ! -f "$duck/duck.gltf" ]; then echo "FAIL: $duck/duck.obj or duck.gltf missing"; exit 1; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# shellcheck disable=SC2054  # the commas are the options' own
camera=(--look-from 2.5,2.2,-2.8 --look-at 0.1,0.8,0 --up 0,1,0 --fov 40 --size 400x400)
for f in obj gltf; do
  if ! "$RAYFORM_BIN" render "$duck/duck.$f" -o "$tmp/$f.png" "${camera[@]}" --depth "2:6:$tmp/${f}_depth.png" \
       --normals "$tmp/${f}_normals.png" --albedo "$tmp/${f}_albedo.png" -q >"$tmp/$f.log" 2>&1; then
    echo "FAIL: rayform failed on duck.$f: $(cat "$tmp/$f.log")"; exit 1
  fi
done

# share of pixels over 4/255 as idiff reports it ("N pixels (P%) over 0.0157")
share() { sed -n 's/.*pixels (\(.*\)%) over 0.0157.*/\1/p' "$1"; }
failn=0
for kind in depth normals albedo colour; do
  a="$tmp/obj_$kind.png" b="$tmp/gltf_$kind.png"
  [ $kind = colour ] && { a="$tmp/obj.png"; b="$tmp/gltf.png"; }
  idiff -v -fail 0.0157 -failpercent 1 "$a" "$b" >"$tmp/$kind.diff" 2>&1; rc=$?
  p=$(share "$tmp/$kind.diff")
  if [ $kind = colour ]; then
    echo "REPORT $kind: ${p:-?}% of pixels differ by more than 4/255 (Phong against metallic-roughness)"
  elif [ $rc -eq 0 ] && [ -n "$p" ]; then
    echo "PASS $kind: ${p}% of pixels differ by more than 4/255 (limit 1%)"
  else
    echo "FAIL $kind: ${p:-?}% of pixels differ by more than 4/255 (limit 1%)"; sed 's/^/    /' "$tmp/$kind.diff"
    failn=$((failn + 1))
  fi
done
[ $failn -eq 0 ]
