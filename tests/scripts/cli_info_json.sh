#!/usr/bin/env bash
# rayform info --json: one JSON object on stdout (parsed here by python3) with
# the values the text shows: format, counts, bounds, extensions, warnings.
# Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# An OBJ of two triangles (one quad) and a missing material library (a
# warning), in a file whose name needs escaping in JSON.
obj='we"ird\name.obj'
printf 'mtllib nothere.mtl\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 -3\nf 1 2 3 4\n' >"$obj"
cat >s.txt <<'SCENE'
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Lights { numLights 1 DirectionalLight { direction -0.3 -0.5 -1 color 0.9 0.9 0.9 } }
Background { color 0.1 0.2 0.3 ambientLight 0.1 0.1 0.1 }
Materials { numMaterials 2 Material { diffuseColor 0.8 0.3 0.2 } Material { diffuseColor 1 1 1 } }
Group { numObjects 2 MaterialIndex 0 Sphere { center 0.5 0 0 radius 0.25 } MaterialIndex 1 Plane { normal 0 1 0 offset -1 } }
SCENE

# check NAME FILE PYTHON-EXPRESSIONS...: info --json FILE parses, and every
# expression (over the object `j`) is true.
check() {
  local name=$1 file=$2 before=$failures; shift 2
  "$RAYFORM_BIN" info --json "$file" >"$name.json" 2>"$name.err" || fail "$name" "exit $?: $(cat "$name.err")"
  python3 -m json.tool "$name.json" >/dev/null 2>&1 || fail "$name" "not JSON: $(cat "$name.json")"
  local e
  for e in "$@"; do
    python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' \
      "$name.json" "$e" 2>/dev/null || fail "$name" "not true: $e in $(cat "$name.json")"
  done
  [ $failures -eq $before ] && echo "ok   [$name] $# values checked"
}

check obj "$obj" \
  "j['scene'] == 'we\"ird\\\\name.obj'" "j['format'] == 'obj'" "'dialect' not in j" \
  "j['triangles'] == {'standalone': 0, 'in_meshes': 2, 'meshes': 1, 'unique_in_meshes': 2}" \
  "j['spheres'] == 0 and j['cameras'] == 0 and j['lights'] == 0" \
  "j['bounds'] == {'min': [0, 0, -3], 'max': [2, 1, 0], 'planes_excluded': False}" \
  "j['extensions'] == []" "len(j['warnings']) == 1 and 'nothere.mtl' in j['warnings'][0]"
check course s.txt \
  "j['format'] == 'course' and j['dialect'] == '2012'" "j['spheres'] == 1 and j['planes'] == 1" \
  "j['materials'] == 2 and j['lights'] == 1 and j['cameras'] == 1 and j['textures'] == 0" \
  "j['triangles']['in_meshes'] == 0" "j['warnings'] == []" \
  "j['bounds'] == {'min': [0.25, -0.25, -0.25], 'max': [0.75, 0.25, 0.25], 'planes_excluded': True}"
# The warnings are in the JSON; -q keeps stderr empty.
"$RAYFORM_BIN" info --json -q "$obj" >q.json 2>q.err || fail quiet "exit $?"
[ -s q.err ] && fail quiet "stderr: $(cat q.err)"
cmp -s q.json obj.json || fail quiet "-q changed the JSON"

# A glTF file: its extensions, each with how it was read.
cat >e.gltf <<'GLTF'
{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_emissive_strength"],
 "scenes": [{"nodes": []}], "scene": 0}
GLTF
check gltf e.gltf "j['format'] == 'gltf'" "j['bounds'] is None" \
  "[e['name'] for e in j['extensions']] == ['KHR_materials_emissive_strength']" \
  "j['extensions'][0]['support'] in ('read', 'approximated', 'ignored')"
# Bad input: a usage error, nothing on stdout.
"$RAYFORM_BIN" info --json=maybe s.txt >bad.json 2>bad.err
rc=$?
[ $rc -eq 2 ] && [ ! -s bad.json ] || fail bad "info --json=maybe: exit $rc, stdout: $(cat bad.json)"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all info --json checks passed"
