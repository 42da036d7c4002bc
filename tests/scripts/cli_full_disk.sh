#!/usr/bin/env bash
# Writing to a full disk (a 16 KB tmpfs): every output format and `convert`
# must exit non-zero with one "cannot write" line, leave no file (nor
# temporary) behind, and leave a previous file of the same name untouched.
# Needs root and a kernel that lets it mount tmpfs (else skipped).
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); full="$tmp/full"; mkdir -p "$full"
trap 'umount "$full" 2>/dev/null; rm -rf "$tmp"' EXIT
if ! mount -t tmpfs -o size=16k tmpfs "$full" 2>/dev/null; then
  echo "SKIPPED: cannot mount a tmpfs here (needs root in a machine or a privileged container)"; exit 77
fi
scene="$RAYFORM_SOURCE_DIR/scenes/default.txt"
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }
printf 'old' >"$full/keep.png"

check() {  # check NAME COMMAND...: must fail with one line, leave only keep.png as it was
  local name=$1; shift
  "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"; local rc=$?
  [ $rc -ne 0 ] || fail "$name" "exit 0"
  grep -q 'cannot write' "$tmp/err.txt" || fail "$name" "no 'cannot write' message: $(cat "$tmp/err.txt")"
  [ "$(grep -c '^rayform: error' "$tmp/err.txt")" -eq 1 ] || fail "$name" "not one error line"
  local left; left=$(cd "$full" && ls -A | grep -v '^keep.png$')
  [ -z "$left" ] || fail "$name" "left behind: $left"
  [ "$(cat "$full/keep.png")" = old ] || fail "$name" "keep.png changed"
  echo "ok [$name]"
}
for ext in png bmp tga hdr exr; do
  check "render .$ext" "$RAYFORM_BIN" render "$scene" -o "$full/x.$ext" --size 200x200 --quiet
done
check "render over keep.png" "$RAYFORM_BIN" render "$scene" -o "$full/keep.png" --size 200x200 --quiet
check "course -depth" "$RAYFORM_BIN" -input "$scene" -size 200 200 -output "$full/c.bmp" -depth 8 12 "$full/d.bmp"
for ext in glb gltf obj txt; do
  check "convert .$ext" "$RAYFORM_BIN" convert "$scene" "$full/s.$ext"
done
[ $failures -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "every write to a full disk failed cleanly"
