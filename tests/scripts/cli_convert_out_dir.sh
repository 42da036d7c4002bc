#!/usr/bin/env bash
# convert --out-dir DIR: the side files (meshes, textures, the .mtl, the .bin)
# go to DIR, the output stays where its positional argument says and names
# them relative to its own folder, so that it reads back whole. DIR must
# exist; a .glb or --embed have no side files: usage errors (exit 2, one line,
# nothing written). Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# A textured OBJ: two materials, one with a texture; 4 triangles.
write_sphere_scene s.txt
"$RAYFORM_BIN" render s.txt -o tex.png --size 8x8 -q || { echo "FAIL: cannot make a texture"; exit 1; }
cat >m.mtl <<'MTL'
newmtl red
Kd 1 0 0
newmtl wood
Kd 1 1 1
map_Kd tex.png
MTL
cat >m.obj <<'OBJ'
mtllib m.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl red
f 1/1 2/2 3/3 4/4
usemtl wood
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 5/1 6/2 7/3 8/4
OBJ

# triangles FILE: the triangle count info --json reads back (and no warning).
triangles() {
  "$RAYFORM_BIN" info --json "$1" 2>/dev/null |
    python3 -c 'import json, sys; j = json.load(sys.stdin); print(j["triangles"]["in_meshes"] + j["triangles"]["standalone"], len(j["warnings"]))'
}
# only_files FOLDER EXPECTED...: the folder holds exactly the files matching these globs (at least one each).
only_files() {
  local dir=$1 f g ok; shift
  for f in "$dir"/* "$dir"/.[!.]*; do
    [ -e "$f" ] || continue
    ok=0; for g in "$@"; do case ${f##*/} in $g) ok=1 ;; esac; done
    [ $ok = 1 ] || { echo "unexpected ${f#"$tmp"/}"; return 1; }
  done
  for g in "$@"; do compgen -G "$dir/$g" >/dev/null || { echo "missing $dir/$g"; return 1; }; done
}

# Course .txt: meshes and textures in a sibling folder, named ../assets/...
mkdir -p out assets
"$RAYFORM_BIN" convert m.obj out/model.txt --out-dir assets -q || fail txt "exit $?"
r=$(only_files out model.txt) || fail txt "$r"
r=$(only_files assets 'model_*.obj' 'model_*.bmp') || fail txt "$r"
grep -q 'obj_file \.\./assets/model_.*\.obj' out/model.txt || fail txt "no obj_file ../assets/...: $(grep -n 'obj_file\|texture' out/model.txt)"
grep -q '\.\./assets/model_.*\.bmp' out/model.txt || fail txt "no texture ../assets/...bmp: $(cat out/model.txt)"
[ "$(triangles out/model.txt)" = "4 0" ] || fail txt "reads back as '$(triangles out/model.txt)' (triangles, warnings), not '4 0'"
"$RAYFORM_BIN" render out/model.txt -o out.png --size 16x16 -q || fail txt "does not render"
[ $failures -eq 0 ] && echo "ok   [txt] out/model.txt + assets/: $(ls assets | tr '\n' ' ')"

# The output in the working folder: its side files named assets/...
before=$failures
"$RAYFORM_BIN" convert m.obj top.txt --out-dir assets -q || fail top "exit $?"
grep -q 'obj_file assets/top_.*\.obj' top.txt || fail top "no obj_file assets/...: $(grep obj_file top.txt)"
[ "$(triangles top.txt)" = "4 0" ] || fail top "reads back as '$(triangles top.txt)', not '4 0'"
[ $failures -eq $before ] && echo "ok   [top] top.txt names assets/top_*"

# OBJ: the .mtl and the texture in a subfolder, mtllib sub/m.mtl.
before=$failures
mkdir -p o/sub
"$RAYFORM_BIN" convert m.obj o/m.obj --out-dir o/sub -q || fail obj "exit $?"
r=$(only_files o m.obj sub) || fail obj "$r"
r=$(only_files o/sub m.mtl 'm_*.png') || fail obj "$r"
grep -qx 'mtllib sub/m.mtl' o/m.obj || fail obj "no 'mtllib sub/m.mtl': $(grep mtllib o/m.obj)"
[ "$(triangles o/m.obj)" = "4 0" ] || fail obj "reads back as '$(triangles o/m.obj)', not '4 0'"
[ $failures -eq $before ] && echo "ok   [obj] o/m.obj + o/sub/: $(ls o/sub | tr '\n' ' ')"

# glTF: the .bin and the image in a folder with a space (URIs percent-encoded).
before=$failures
mkdir -p g "g/side files"
"$RAYFORM_BIN" convert m.obj g/m.gltf --out-dir "g/side files" -q || fail gltf "exit $?"
r=$(only_files g m.gltf 'side files') || fail gltf "$r"
r=$(only_files "g/side files" m.bin 'm_*.png') || fail gltf "$r"
python3 - g/m.gltf <<'PY' || fail gltf "URIs: $(grep uri g/m.gltf)"
import json, sys
j = json.load(open(sys.argv[1]))
ok = [b['uri'] for b in j['buffers']] == ['side%20files/m.bin'] and j['images'] and \
     all(i['uri'].startswith('side%20files/m_') for i in j['images'])
sys.exit(0 if ok else 1)
PY
[ "$(triangles g/m.gltf)" = "4 0" ] || fail gltf "reads back as '$(triangles g/m.gltf)', not '4 0'"
[ $failures -eq $before ] && echo "ok   [gltf] g/m.gltf + 'g/side files/': $(ls "g/side files" | tr '\n' ' ')"

# Without --out-dir: beside the output, as before.
before=$failures
mkdir -p b
"$RAYFORM_BIN" convert m.obj b/m.gltf -q || fail beside "exit $?"
r=$(only_files b m.gltf m.bin 'm_*.png') || fail beside "$r"
grep -q '"uri": "m.bin"' b/m.gltf || fail beside "$(grep uri b/m.gltf)"
[ $failures -eq $before ] && echo "ok   [beside] without --out-dir: $(ls b | tr '\n' ' ')"

# Usage errors: exit 2, one line naming --out-dir, nothing written.
: >afile
usage() {
  local name=$1 pattern=$2 out=$3; shift 3
  local before=$failures
  "$RAYFORM_BIN" convert m.obj "$out" "$@" >/dev/null 2>"$name.err"
  local rc=$?
  [ $rc -eq 2 ] || fail "$name" "exit $rc, expected 2"
  local msg
  msg=$(grep -v -e "^(run 'rayform --help' for usage)$" "$name.err")
  [ "$(printf '%s\n' "$msg" | grep -c '')" -eq 1 ] || fail "$name" "not one line: $(cat "$name.err")"
  grep -qE -- "$pattern" <<<"$msg" || fail "$name" "does not match /$pattern/: $msg"
  [ -e "$out" ] && fail "$name" "$out was written"
  [ $failures -eq $before ] && echo "ok   [$name] exit 2: $msg"
}
usage missing-dir "^rayform: --out-dir: folder 'nothere' does not exist$" e1.txt --out-dir nothere
usage a-file "^rayform: --out-dir: folder 'afile' does not exist$" e2.txt --out-dir afile
usage empty "^rayform: --out-dir expects a folder" e3.txt --out-dir ''
usage glb "^rayform: --out-dir: a \.glb holds everything" e4.glb --out-dir assets
usage embed "^rayform: --out-dir: with --embed" e5.gltf --out-dir assets --embed
usage no-value "--out-dir" e6.txt --out-dir
mkdir -p "with space"
usage course-space "^rayform: --out-dir: a course \.txt cannot name files in 'with space'" e7.txt --out-dir "with space"
left=$(find . -name 'e[0-9]*' -o -name '.*tmp*')
[ -z "$left" ] || fail usage "left behind: $left"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all convert --out-dir checks passed"
