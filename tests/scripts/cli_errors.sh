#!/usr/bin/env bash
# The command line on bad input: every case must exit non-zero (without
# crashing), print ONE message line naming the problem (file:line:column for
# scene errors; the usage hint line of the CLI is allowed besides it), and
# leave NO file behind in the output folder, not even a temporary one.
# Also: the course flags work in any order and give the same picture.
# Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
in="$tmp/in"; mkdir -p "$in"

write_sphere_scene "$in/ok.txt"
# Line 4, column 23: 'radius' where the third coordinate should be.
cat >"$in/bad.txt" <<'EOF'
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Group {
  numObjects 1
  Sphere { center 0 0 radius 1 }
}
EOF
# Line 3, column 14: MaterialIndex 1 with one material.
cat >"$in/badindex.txt" <<'EOF'
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Materials { numMaterials 1 Material { } }
Group { numObjects 1 MaterialIndex 1 Sphere { radius 1 } }
EOF
# Line 2, column 1: end of file inside the Group.
printf 'PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }\nGroup { numObjects 1' >"$in/truncated.txt"

failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# expect_failure NAME REGEX ARGS...: runs rayform ARGS in an empty folder.
expect_failure() {
  local name=$1 pattern=$2; shift 2
  local out="$tmp/out-$name" before=$failures
  mkdir -p "$out"
  (cd "$out" && "$RAYFORM_BIN" "$@") >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  last_rc=$rc
  if [ $rc -eq 0 ]; then fail "$name" "exit status 0"; fi
  if [ $rc -ge 128 ]; then fail "$name" "crashed (exit status $rc)"; fi
  # Message lines: everything on stderr but the usage hints.
  local msg
  msg=$(grep -v -e "^(run 'rayform --help' for usage)$" -e '^Run with --help for more information\.$' -e '^$' "$tmp/stderr")
  local n
  n=$(printf '%s' "$msg" | grep -c '')
  if [ "$n" -ne 1 ]; then fail "$name" "expected one message line, got $n: $(cat "$tmp/stderr")"; fi
  if ! grep -qE -- "$pattern" <<<"$msg"; then fail "$name" "message does not match /$pattern/: $msg"; fi
  local left
  left=$(ls -A "$out")
  if [ -n "$left" ]; then fail "$name" "files left behind: $left"; fi
  [ $failures -eq $before ] && echo "ok   [$name] exit $rc: $msg"
}

# expect_usage_error NAME REGEX ARGS...: expect_failure, with exit status 2 (usage).
expect_usage_error() {
  expect_failure "$@"
  [ "$last_rc" -eq 2 ] || fail "$1" "exit status $last_rc, expected 2 (usage)"
}

ok="$in/ok.txt"
# Image size.
expect_failure size-zero '-size.*positive' -input "$ok" -size 0 20 -output o.png
expect_failure size-zero-height '-size.*positive' -input "$ok" -size 20 0 -output o.png
expect_failure size-negative '-size.*positive' -input "$ok" -size -20 20 -output o.png
expect_failure size-missing-height '-size' -input "$ok" -size 20 -output o.png
expect_failure size-not-a-number "-size.*'x'" -input "$ok" -size 20 x -output o.png
expect_failure render-size-zero '--size.*0x20' render "$ok" -o o.png --size 0x20
expect_failure render-size-negative '--size' render "$ok" -o o.png --size 20x-3
# Options.
expect_failure unknown-option "unknown option '-bogus'" -input "$ok" -size 20 20 -output o.png -bogus
expect_failure unknown-option-first "unknown option '-inptu'|-inptu" -inptu "$ok" -size 20 20 -output o.png
expect_failure render-unknown-option 'bogus' render "$ok" -o o.png --bogus
expect_failure missing-input 'missing -input' -size 20 20 -output o.png
expect_failure missing-output 'missing -output' -input "$ok" -size 20 20
expect_failure render-missing-output 'output' render "$ok" --size 20x20
expect_failure depth-range 'MAX > MIN|depth' -input "$ok" -size 20 20 -output o.png -depth 12 8 d.png
# Camera option values: one line naming the option and what it expects, exit 2.
expect_usage_error look-from-not-a-number "^rayform: --look-from expects three numbers X,Y,Z, got '3,x,3'$" render "$ok" -o o.png --look-from 3,x,3
expect_usage_error look-from-nan "--look-from expects three numbers" render "$ok" -o o.png --look-from 0,nan,1
orbit_numbers="^rayform: --orbit expects two or three numbers AZ,EL\[,DIST\], got"
expect_usage_error orbit-one-number "$orbit_numbers '1'$" render "$ok" -o o.png --orbit 1
expect_usage_error orbit-four-numbers "$orbit_numbers '1,2,3,4'$" render "$ok" -o o.png --orbit 1,2,3,4
expect_usage_error orbit-letters "$orbit_numbers 'a,b'$" render "$ok" -o o.png --orbit a,b
expect_usage_error orbit-empty "$orbit_numbers ''$" render "$ok" -o o.png --orbit ''
expect_usage_error orbit-trailing-comma "$orbit_numbers '0,0,'$" render "$ok" -o o.png --orbit 0,0,
expect_usage_error orbit-nan "$orbit_numbers 'nan,0'$" render "$ok" -o o.png --orbit nan,0
expect_usage_error orbit-inf "$orbit_numbers '0,inf'$" render "$ok" -o o.png --orbit 0,inf
expect_usage_error orbit-inf-distance "$orbit_numbers '0,0,-inf'$" render "$ok" -o o.png --orbit 0,0,-inf
orbit_el="^rayform: --orbit AZ,EL\[,DIST\]: elevation EL must lie strictly between -90 and 90 degrees, got"
expect_usage_error orbit-el-90 "$orbit_el '0,90'$" render "$ok" -o o.png --orbit 0,90
expect_usage_error orbit-el-minus-90 "$orbit_el '0,-90'$" render "$ok" -o o.png --orbit=0,-90
expect_usage_error orbit-el-120 "$orbit_el '10,120,3'$" render "$ok" -o o.png --orbit 10,120,3
orbit_dist="^rayform: --orbit AZ,EL\[,DIST\]: distance DIST must be a finite number greater than 0, got"
expect_usage_error orbit-dist-negative "$orbit_dist '0,10,-1'$" render "$ok" -o o.png --orbit 0,10,-1
expect_usage_error orbit-dist-zero "$orbit_dist '0,10,0'$" render "$ok" -o o.png --orbit 0,10,0
expect_usage_error orbit-and-look-from "^rayform: --orbit .*cannot be combined with --look-from or --look-at$" render "$ok" -o o.png --orbit 0,0 --look-from 1,2,3
expect_usage_error orbit-and-look-at "^rayform: --orbit .*cannot be combined with --look-from or --look-at$" render "$ok" -o o.png --look-at 0,0,0 --orbit 0,0
expect_usage_error orbit-and-camera "^rayform: --orbit .*cannot be combined with --camera$" render "$ok" -o o.png --orbit 0,0 --camera 0
expect_usage_error frame-and-camera "^rayform: --frame .*cannot be combined with --camera$" render "$ok" -o o.png --camera 1 --frame
# One exit-status scheme (README "Exit status"): CLI11's own parse errors and
# every bad option value are usage errors: exit 2, one line naming the option.
expect_usage_error filter-bogus "^rayform: --filter: bogus not in" render "$ok" -o o.png --filter bogus
expect_usage_error render-bogus-option "--bogus" render "$ok" -o o.png --bogus
expect_usage_error no-subcommand "subcommand"
expect_usage_error unknown-subcommand "rendr|subcommand" rendr "$ok"
expect_usage_error render-no-scene "scene is required" render -o o.png
expect_usage_error render-bad-camera-index "^rayform: --camera" render "$ok" -o o.png --camera 3 --fov 30
expect_usage_error render-threads-not-a-number "--threads" render "$ok" -o o.png --threads many
expect_usage_error fov-200 "^rayform: --fov expects degrees strictly between 0 and 180, got '200'$" render "$ok" -o o.png --fov 200
expect_usage_error fov-0 "^rayform: --fov expects degrees strictly between 0 and 180, got '0'$" render "$ok" -o o.png --fov 0
expect_usage_error up-parallel "^rayform: --up must not be parallel" render "$ok" -o o.png --look-from 0,8,0 --up 0,1,0
expect_usage_error look-at-is-look-from "^rayform: --look-at must differ from --look-from$" render "$ok" -o o.png --look-from 1,2,3 --look-at 1,2,3
expect_usage_error output-extension-render "o\.xyz" render "$ok" -o o.xyz
# --background: R,G,B in 0..1 or #RRGGBB, never clamped.
bg_expects="^rayform: --background expects R,G,B with each 0..1 or #RRGGBB, got"
expect_usage_error background-255 "$bg_expects '255,255,255'$" render "$ok" -o o.png --background 255,255,255
expect_usage_error background-above-1 "$bg_expects '0,1.5,0'$" render "$ok" -o o.png --background 0,1.5,0
expect_usage_error background-negative "$bg_expects '0,-0.1,0'$" render "$ok" -o o.png --background 0,-0.1,0
expect_usage_error background-two "$bg_expects '0.5,0.5'$" render "$ok" -o o.png --background 0.5,0.5
expect_usage_error background-nan "$bg_expects 'nan,0,0'$" render "$ok" -o o.png --background nan,0,0
expect_usage_error background-empty "$bg_expects ''$" render "$ok" -o o.png --background ''
expect_usage_error background-hex-short "$bg_expects '#fff'$" render "$ok" -o o.png --background '#fff'
# Adaptive sampling and the sampler (RenderOptions' one check, under each command line's names).
expect_usage_error target-error-zero "^rayform: --target-error: must be a positive number" render "$ok" -o o.png --target-error 0
expect_usage_error target-error-negative "^rayform: --target-error: must be a positive number" render "$ok" -o o.png --target-error -0.01
expect_usage_error target-error-nan "^rayform: --target-error: must be a positive number, got -?nan" render "$ok" -o o.png --target-error nan
expect_usage_error target-error-tent "^rayform: --target-error: adaptive sampling uses the box filter" render "$ok" -o o.png --target-error 0.01 --filter tent
expect_usage_error max-spp-zero "^rayform: --max-spp: must be at least 1, got 0$" render "$ok" -o o.png --target-error 0.01 --max-spp 0
expect_usage_error sampler-bogus "^rayform: --sampler: bogus not in" render "$ok" -o o.png --sampler bogus
expect_usage_error course-target-error-zero "^rayform: -target-error: must be a positive number" -input "$ok" -size 20 20 -output o.png -target-error 0
expect_usage_error course-target-error-nan "^rayform: -target-error expects a positive error per channel, got 'nan'$" -input "$ok" -size 20 20 -output o.png -target-error nan
expect_usage_error course-max-spp-zero "^rayform: -max-spp: must be at least 1, got 0$" -input "$ok" -size 20 20 -output o.png -max-spp 0
expect_usage_error course-sampler-bogus "^rayform: -sampler expects stratified or random, got 'x'$" -input "$ok" -size 20 20 -output o.png -sampler x
expect_usage_error course-jitter-spp "^rayform: -spp: the 3x3 samples per pixel of -jitter/-filter cannot be combined" -input "$ok" -size 20 20 -output o.png -jitter -spp 4
expect_usage_error background-hex-letters "$bg_expects '#12345g'$" render "$ok" -o o.png --background '#12345g'
expect_usage_error background-hex-long "$bg_expects '#1234567'$" render "$ok" -o o.png --background '#1234567'
# --transparent: only outputs with alpha; refused before the scene is read (a missing one is not reported).
for ext in bmp jpg hdr; do
  expect_usage_error transparent-$ext "^rayform: --transparent: o\.$ext cannot hold alpha \(write \.png, \.tga, \.exr or \.tif\)$" \
    render "$in/nothere.txt" -o o.$ext --transparent
done
expect_usage_error info-bogus-option "--bogus" info "$ok" --bogus
expect_usage_error convert-segments "^rayform: --sphere-segments" convert "$ok" o.obj --sphere-segments 2
expect_usage_error convert-output-extension "o\.xyz: unknown scene format" convert "$ok" o.xyz
expect_usage_error convert-output-folder "nofolder/o\.obj.*nofolder" convert "$ok" nofolder/o.obj
expect_usage_error convert-missing-output "output is required" convert "$ok"
expect_usage_error course-size-zero "-size.*positive" -input "$ok" -size 0 20 -output o.png
expect_usage_error course-unknown-option "unknown option '-bogus'" -input "$ok" -size 20 20 -output o.png -bogus
# A scene that is missing: an input error (exit 1), worded the same by every command.
missing_message="^rayform: error: $in/nothere\.txt: cannot open scene file: no such file$"
for cmd in render convert info course; do
  case $cmd in
    render) args=(render "$in/nothere.txt" -o o.png) ;;
    convert) args=(convert "$in/nothere.txt" o.obj) ;;
    info) args=(info "$in/nothere.txt") ;;
    course) args=(-input "$in/nothere.txt" -size 20 20 -output o.png) ;;
  esac
  expect_failure "missing-scene-$cmd" "$missing_message" "${args[@]}"
  [ "$last_rc" -eq 1 ] || fail "missing-scene-$cmd" "exit status $last_rc, expected 1 (input error)"
done
mkdir -p "$in/folder.txt"
expect_failure missing-scene-folder "^rayform: error: $in/folder\.txt: cannot open scene file: it is a folder$" convert "$in/folder.txt" o.obj
# --help and --version succeed; --help documents the scheme.
"$RAYFORM_BIN" --help >"$tmp/help" 2>&1 || fail help "exit status $?"
grep -q '^Exit status:' "$tmp/help" || fail help "--help has no 'Exit status:' footer"
"$RAYFORM_BIN" --version >/dev/null 2>&1 || fail version "exit status $?"
# Unwritable outputs.
expect_failure output-folder-missing "nofolder/o.png.*nofolder" -input "$ok" -size 20 20 -output nofolder/o.png
expect_failure output-unknown-extension "o\.xyz" -input "$ok" -size 20 20 -output o.xyz
expect_failure depth-folder-missing "nofolder/d.png" -input "$ok" -size 20 20 -output o.png -depth 8 12 nofolder/d.png
expect_failure normals-unknown-extension "n\.xyz" -input "$ok" -size 20 20 -output o.png -normals n.xyz
# The output names an existing folder: that folder must stay untouched.
mkdir -p "$tmp/taken.png"
expect_failure output-is-a-folder "taken\.png" -input "$ok" -size 20 20 -output "$tmp/taken.png"
[ -d "$tmp/taken.png" ] && [ -z "$(ls -A "$tmp/taken.png")" ] || fail output-is-a-folder "the folder was changed"
# A later output that cannot be written must not leave the earlier ones
# behind (/proc accepts no new files, even from root).
expect_failure normals-unwritable "/proc/n\.png" -input "$ok" -size 20 20 -output o.png -depth 8 12 d.png -normals /proc/n.png
expect_failure depth-unwritable "/proc/d\.png" -input "$ok" -size 20 20 -output o.png -depth 8 12 /proc/d.png
# Bad scenes: the message names file:line:column.
expect_failure scene-missing "nothere\.txt" -input "$in/nothere.txt" -size 20 20 -output o.png
expect_failure scene-unknown-format "scene\.xyz" -input "$in/scene.xyz" -size 20 20 -output o.png
expect_failure scene-malformed "$in/bad\.txt:4:23: expected a number, found 'radius'" -input "$in/bad.txt" -size 20 20 -output o.png
expect_failure scene-malformed-render "$in/bad\.txt:4:23: " render "$in/bad.txt" -o o.png --size 20x20
expect_failure scene-material-index "$in/badindex\.txt:3:36: MaterialIndex 1 is out of range" -input "$in/badindex.txt" -size 20 20 -output o.png
expect_failure scene-truncated "$in/truncated\.txt:2:21: unexpected end of file" -input "$in/truncated.txt" -size 20 20 -output o.png -depth 8 12 d.png -normals n.png

# Course flags in any order: the same three pictures, byte for byte.
order_dir="$tmp/order"; mkdir -p "$order_dir"
run_order() {
  local tag=$1; shift
  (cd "$order_dir" && "$RAYFORM_BIN" "$@") >"$tmp/stdout" 2>"$tmp/stderr" || fail "order-$tag" "exit $?: $(cat "$tmp/stderr")"
}
run_order a -input "$ok" -size 24 16 -output a.png -depth 8 12 a_d.png -normals a_n.png
run_order b -normals b_n.png -output b.png -depth 8 12 b_d.png -size 24 16 -input "$ok"
run_order c -depth 8 12 c_d.png -input "$ok" -normals c_n.png -size 24 16 -output c.png
run_order d -output d.png -size 24 16 -normals d_n.png -input "$ok" -depth 8 12 d_d.png
for t in b c d; do
  for suffix in "" _d _n; do
    if ! cmp -s "$order_dir/a$suffix.png" "$order_dir/$t$suffix.png"; then fail "order-$t" "$t$suffix.png differs from a$suffix.png"; fi
  done
done
before=$failures
size=$(oiiotool "$order_dir/a.png" --echo "{TOP.width}x{TOP.height}" 2>/dev/null)
[ "$size" = "24x16" ] || fail order "a.png is '$size', not 24x16"
[ "$(ls -A "$order_dir" | wc -l)" -eq 12 ] || fail order "expected exactly the 12 pictures, found: $(ls -A "$order_dir")"
[ $failures -eq $before ] && echo "ok   [order] flags in four orders give identical pictures"

# The a5 dialect's bad input (COURSE_FORMAT.md "2012 assignment 5"): one line
# with file:line:column, exit 1, no picture. Cube map faces are made by
# rayform itself (2x2 and 4x4 .bmp pictures of the sphere scene).
a5="$tmp/a5"; mkdir -p "$a5/sky" "$a5/oddsky"
for face in right left up down front back; do
  "$RAYFORM_BIN" -input "$in/ok.txt" -size 2 2 -output "$a5/sky/$face.bmp" -quiet
  "$RAYFORM_BIN" -input "$in/ok.txt" -size 2 2 -output "$a5/oddsky/$face.bmp" -quiet
done
"$RAYFORM_BIN" -input "$in/ok.txt" -size 4 4 -output "$a5/oddsky/up.bmp" -quiet
rm "$a5/sky/down.bmp"
camera='PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }'
printf '%s\nMaterials { numMaterials 1\n  Material { refractionIndex -1.3 } }\nGroup { numObjects 0 }\n' "$camera" >"$a5/refraction.txt"
printf '%s\nMaterials { numMaterials 1 Material {\n  Noise { color 1 0 0 color 0 1 0 octaves -1 } } }\nGroup { numObjects 0 }\n' "$camera" >"$a5/octaves.txt"
printf '%s\nMaterials { numMaterials 1 Material {\n  Noise { color 1 0 0 octaves 2 } } }\nGroup { numObjects 0 }\n' "$camera" >"$a5/colour.txt"
printf '%s\nBackground {\n  cubeMap sky }\nGroup { numObjects 0 }\n' "$camera" >"$a5/face.txt"
printf '%s\nBackground {\n  cubeMap oddsky }\nGroup { numObjects 0 }\n' "$camera" >"$a5/size.txt"
expect_failure a5-refraction-negative "refraction\.txt:3:30: refractionIndex must be 0 \(opaque\) or positive" -input "$a5/refraction.txt" -size 8 8 -output o.png -dialect a5
expect_failure a5-noise-octaves "octaves\.txt:3:43: octaves must be a whole number" -input "$a5/octaves.txt" -size 8 8 -output o.png
expect_failure a5-noise-colour "colour\.txt:3:3: Noise needs two colours" render "$a5/colour.txt" -o o.png --size 8x8
expect_failure a5-cube-face-missing "face\.txt:3:11: cube map folder has no down\.bmp" -input "$a5/face.txt" -size 8 8 -output o.png
expect_failure a5-cube-face-size "up\.bmp \(4x4\): cube map face of another size than .*right\.bmp \(2x2\)" -input "$a5/size.txt" -size 8 8 -output o.png
expect_usage_error a5-dialect-bogus "^rayform: -dialect expects 2012, 2019 or a5, got 'a6'$" -input "$a5/size.txt" -size 8 8 -output o.png -dialect a6

# No temporary picture anywhere (they are written beside the target as
# .NAME.tmpPID.EXT, e.g. beside taken.png above).
stray=$(find "$tmp" -name '.*.tmp*')
[ -z "$stray" ] || fail temporaries "left behind: $stray"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all CLI error checks passed"
