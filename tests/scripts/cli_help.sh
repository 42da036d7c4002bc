#!/usr/bin/env bash
# `rayform --help` lists every option of every subcommand (the README says it
# does), the README names every option --help lists, and every option the
# README's "Modern usage" and "Conversion" sections name is one --help lists.
# Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }
readme=$RAYFORM_SOURCE_DIR/README.md

# Long options as a help text lists them ("  -o,--output TEXT ...", "  --flat ...").
listed() { grep -oE '^ +(-[a-zA-Z],)?--[a-z][a-z-]*' | grep -oE -- '--[a-z][a-z-]*' | sort -u; }

"$RAYFORM_BIN" --help >"$tmp/help" 2>&1 || fail help "rayform --help: exit $?"
listed <"$tmp/help" >"$tmp/top"
for sub in render info convert; do
  "$RAYFORM_BIN" "$sub" --help >"$tmp/$sub" 2>&1 || fail "$sub" "rayform $sub --help: exit $?"
  before=$failures
  for o in $(listed <"$tmp/$sub" | grep -vx -e --help); do
    grep -qx -- "$o" "$tmp/top" || fail "$sub" "rayform --help does not list $sub's $o"
    grep -q -- "$o\b" "$readme" || fail "$sub" "README.md does not name $sub's $o"
  done
  [ $failures -eq $before ] && echo "ok   [$sub] $(listed <"$tmp/$sub" | grep -c '') options in rayform --help and README.md"
done

# The options the README's usage sections name.
before=$failures
sections=$(awk '/^## /{on = ($0 ~ /^## (Modern usage|Conversion)/)} on' "$readme")
for o in $(grep -oE -- '--[a-z][a-z-]*' <<<"$sections" | sort -u); do
  [ "$o" = --help ] || [ "$o" = --version ] && continue
  grep -qx -- "$o" "$tmp/top" || fail readme "README.md names $o, which rayform --help does not list"
done
[ $failures -eq $before ] && echo "ok   [readme] every option the README's usage sections name is in rayform --help"
# The exit statuses, in --help and the README.
grep -q '^Exit status:' "$tmp/help" || fail exit-status "rayform --help has no 'Exit status:' section"
grep -q '^## Exit status' "$readme" || fail exit-status "README.md has no '## Exit status' section"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all help checks passed"
