#!/usr/bin/env bash
# -q/--quiet (the course line's -quiet): nothing on stderr but errors, in
# every command: no warnings, notes or progress. Without it the same runs do
# print their warnings and notes (so the scenes below do provoke them), and
# with it an error still prints. Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

# An OBJ with a missing material library (warnings), no camera and no light (notes).
printf 'mtllib nothere.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >t.obj

failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# check NAME ARGS...: quiet with QUIET_FLAG appended: exit 0, stderr empty;
# without it: exit 0 and some warning or note on stderr.
check() {
  local name=$1 flag=$2 before=$failures; shift 2
  "$RAYFORM_BIN" "$@" >"$name.out" 2>"$name.loud"
  local rc=$?
  [ $rc -eq 0 ] || fail "$name" "without $flag: exit $rc: $(cat "$name.loud")"
  grep -qE '^(warning|note): ' "$name.loud" || fail "$name" "without $flag: no warning or note to silence"
  "$RAYFORM_BIN" "$@" "$flag" >"$name.out" 2>"$name.err"
  rc=$?
  [ $rc -eq 0 ] || fail "$name" "with $flag: exit $rc"
  [ -s "$name.err" ] && fail "$name" "with $flag, stderr is not empty: $(cat "$name.err")"
  [ $failures -eq $before ] && echo "ok   [$name] $flag silences $(grep -c '' "$name.loud") line(s)"
}

check render -q render t.obj -o r.png --size 16x16
check render-long --quiet render t.obj -o r.png --size 16x16
check info -q info t.obj
grep -q '^triangles:' info.out || fail info "with -q, info printed no counts on stdout"
check convert -q convert t.obj c.txt
check convert-glb --quiet convert t.obj c.glb
check course -quiet -input t.obj -size 16 16 -output k.png
# -q/--quiet before the subcommand: the same as after it.
for flag in -q --quiet; do
  for sub in render info convert; do
    case $sub in
      render) args=(render t.obj -o r.png --size 16x16) ;;
      info) args=(info t.obj) ;;
      convert) args=(convert t.obj c.txt) ;;
    esac
    "$RAYFORM_BIN" $flag "${args[@]}" >before.out 2>before.err
    rc=$?
    if [ $rc -ne 0 ] || [ -s before.err ]; then
      fail "before-$sub" "rayform $flag ${args[*]}: exit $rc, stderr: $(cat before.err)"
    else
      echo "ok   [before-$sub] rayform $flag $sub ...: exit 0, stderr empty"
    fi
  done
done

# Errors still print.
"$RAYFORM_BIN" render nothere.txt -o e.png -q 2>err.log
rc=$?
[ $rc -eq 1 ] && grep -q 'nothere.txt' err.log || fail error "render -q of a missing scene: exit $rc, stderr: $(cat err.log)"
"$RAYFORM_BIN" -input nothere.txt -size 16 16 -output e.png -quiet 2>err.log
rc=$?
[ $rc -eq 1 ] && grep -q 'nothere.txt' err.log || fail error-course "-quiet, missing scene: exit $rc, stderr: $(cat err.log)"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all quiet checks passed"
