#!/usr/bin/env bash
# The progress line, on a terminal (a pty from util-linux `script`): it shows
# the time elapsed and an estimate of the time left, ends "done in"; a run
# interrupted by SIGINT (Ctrl-C) ends the line with a newline, then prints its
# one-line message, and leaves no picture or temporary behind. Without a
# terminal there is no progress line. Needs no third-party data.
source "$(dirname "$0")/lib.sh"
command -v script >/dev/null || { echo "SKIPPED: script (util-linux) not found"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
write_sphere_scene s.txt
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }
# on_terminal LOG COMMAND: runs COMMAND with stdin, stdout and stderr on a pty; its output in LOG.
on_terminal() { script -qfec "$2" /dev/null </dev/null >"$1" 2>&1; }

# A render that finishes: percentages with elapsed and remaining time, then "done in".
on_terminal done.log "'$RAYFORM_BIN' render s.txt -o done.png --size 400x400 --spp 4 --threads 1"
[ -f done.png ] || fail done "no picture: $(cat done.log)"
grep -qE 'rendering +[0-9]+%  [0-9]+:[0-9]{2} elapsed' done.log || fail done "no elapsed time: $(cat -v done.log)"
grep -qE 'elapsed, about [0-9]+:[0-9]{2} left' done.log || fail done "no estimate of the time left: $(cat -v done.log)"
grep -qE 'rendering done in [0-9]+:[0-9]{2}' done.log || fail done "no 'done in' line: $(cat -v done.log)"
[ $failures -eq 0 ] && echo "ok   [done] $(tr '\r' '\n' <done.log | grep -c elapsed) progress updates, then 'done in'"

# Interrupted (SIGINT after 2 s of a render of a minute or more).
before=$failures
on_terminal int.log "timeout -s INT 2 '$RAYFORM_BIN' render s.txt -o int.png --size 4000x4000 --spp 64 --threads 1"
grep -q 'elapsed' int.log || fail interrupt "no progress line before the interrupt: $(cat -v int.log)"
# The pty turns \n into \r\n: the message must stand alone on its line.
python3 - int.log <<'PY' || fail interrupt "the message does not follow a newline: $(cat -v int.log)"
import sys
lines = open(sys.argv[1], 'rb').read().decode().split('\n')
hits = [i for i, l in enumerate(lines) if 'interrupted' in l]
ok = len(hits) == 1 and lines[hits[0]].rstrip('\r') == 'rayform: interrupted' and 'elapsed' in lines[hits[0] - 1]
sys.exit(0 if ok else 1)
PY
left=$(ls -A | grep -v -e '^s\.txt$' -e '^done\.png$' -e '\.log$')
[ -z "$left" ] || fail interrupt "files left behind: $left"
[ $failures -eq $before ] && echo "ok   [interrupt] progress line ended, then: $(grep -a interrupted int.log | tr -d '\r')"

# Not a terminal: no progress line.
"$RAYFORM_BIN" render s.txt -o plain.png --size 64x64 2>plain.log || fail plain "exit $?"
[ -s plain.log ] && fail plain "stderr is not a terminal, yet: $(cat -v plain.log)"

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all progress checks passed"
