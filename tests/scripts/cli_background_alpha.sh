#!/usr/bin/env bash
# render --background and --transparent, checked on the written files' bytes
# (PNG decoded by python3's zlib and struct, TGA read as is):
# - --background takes display values: in an asset scene (linear, written as
#   sRGB) the background pixel of an 8-bit file is exactly the byte asked for,
#   as #RRGGBB (all 256 values, also with --spp 16) or R,G,B in 0..1
#   (floor(v * 255)); in a course scene (raw values) the same bytes;
# - --transparent writes 4 channels: alpha 0 on the background (its colour the
#   background's), 255 inside the model, between 0 and 255 on an edge with --spp.
# The usage errors of both options are in cli_errors.sh. Needs no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
command -v python3 >/dev/null || { echo "SKIPPED: python3 not found"; exit 77; }

failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# A triangle around the origin (no camera, no light: rayform adds both); the
# image corners show the background.
printf 'v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
write_sphere_scene sphere.txt

# pixels FILE X,Y ... [FILE X,Y ...]: for each file its number of channels,
# then the values of each pixel named after it, one line each.
cat >pixels.py <<'PY'
import struct, sys, zlib
def read_png(path):
    d = open(path, 'rb').read()
    assert d[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
    i, idat = 8, b''
    while i < len(d):
        n, t = struct.unpack('>I4s', d[i:i + 8])
        c = d[i + 8:i + 8 + n]
        i += 12 + n
        if t == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', c[:10])
            assert depth == 8, 'not 8-bit'
        elif t == b'IDAT':
            idat += c
    ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw, stride, rows, prev, o = zlib.decompress(idat), w * ch, [], bytearray(w * ch), 0
    for _ in range(h):
        f, line = raw[o], bytearray(raw[o + 1:o + 1 + stride])
        o += 1 + stride
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, ch, lambda x, y: list(rows[y][x * ch:(x + 1) * ch])
def read_tga(path):  # uncompressed or RLE true-colour, as stb writes it
    d = open(path, 'rb').read()
    idlen, ctype, w, h, bpp, desc = d[0], d[2], *struct.unpack('<HH', d[12:16]), d[16], d[17]
    ch, px, i = bpp // 8, [], 18 + idlen
    while len(px) < w * h:
        if ctype == 2:
            px.append(d[i:i + ch]); i += ch
        else:
            head = d[i]; i += 1; n = (head & 127) + 1
            if head & 128:
                px += [d[i:i + ch]] * n; i += ch
            else:
                px += [d[i + k * ch:i + (k + 1) * ch] for k in range(n)]; i += n * ch
    top = desc & 32
    def at(x, y):
        p = list(px[(y if top else h - 1 - y) * w + x])
        return [p[2], p[1], p[0]] + p[3:]  # BGR(A) -> RGB(A)
    return w, ch, at
for arg in sys.argv[1:]:
    if arg[0].isdigit():
        x, y = map(int, arg.split(','))
        print(' '.join(map(str, at(x, y))))
    else:
        w, ch, at = (read_tga if arg.endswith('.tga') else read_png)(arg)
        print(ch)
PY
pixels() { python3 pixels.py "$@"; }

# --background as #RRGGBB: every byte value 0..255, in an asset scene and a
# course scene, and with 16 samples per pixel (whose average must be exact).
before=$failures
for run in "tri.obj 1" "sphere.txt 1" "tri.obj 16"; do
  read -r scene spp <<<"$run"
  files=() want=()
  for ((v = 0; v < 256; v += 3)); do
    want+=("$v $(((v + 1) % 256)) $(((v + 2) % 256))")
    hex=$(printf '#%02x%02x%02x' $v $(((v + 1) % 256)) $(((v + 2) % 256)))
    files+=("bg-$v.png" "0,0")
    "$RAYFORM_BIN" render "$scene" -o "bg-$v.png" --size 8x8 --spp "$spp" --background "$hex" -q 2>err.log ||
      { fail "hex-$scene" "--background '$hex': exit $?: $(cat err.log)"; break; }
  done
  [ $failures -eq $before ] || break
  mapfile -t got < <(pixels "${files[@]}" | grep ' ')
  for i in "${!want[@]}"; do
    [ "${got[$i]:-}" = "${want[$i]}" ] || fail "hex-$scene-spp$spp" "corner pixel ${got[$i]:-none}, expected ${want[$i]}"
  done
done
[ $failures -eq $before ] && echo "ok   [hex] --background #RRGGBB: the corner pixel is the bytes asked for (0..255, asset and course scenes, --spp 1 and 16)"

# --background as R,G,B in 0..1: floor(v * 255) per channel.
before=$failures
for scene in tri.obj sphere.txt; do
  "$RAYFORM_BIN" render $scene -o bg.png --size 8x8 --background 0.5,0.25,1 -q 2>err.log || fail "floats-$scene" "exit $?: $(cat err.log)"
  corner=$(pixels bg.png 0,0 | tail -1)
  [ "$corner" = "127 63 255" ] || fail "floats-$scene" "--background 0.5,0.25,1: corner pixel $corner, expected 127 63 255"
  "$RAYFORM_BIN" render $scene -o bg.png --size 8x8 --background 0,0,0 -q 2>err.log || fail "floats-$scene" "exit $?: $(cat err.log)"
  corner=$(pixels bg.png 0,0 | tail -1)
  [ "$corner" = "0 0 0" ] || fail "floats-$scene" "--background 0,0,0: corner pixel $corner, expected 0 0 0"
done
[ $failures -eq $before ] && echo "ok   [floats] --background R,G,B: the corner pixel is floor(v * 255)"

# --transparent: PNG and TGA with 4 channels, alpha 0 at the corner, 255 at the centre.
before=$failures
for ext in png tga; do
  "$RAYFORM_BIN" render tri.obj -o t.$ext --size 32x32 --background '#336699' --transparent -q 2>err.log ||
    { fail "transparent-$ext" "exit $?: $(cat err.log)"; continue; }
  mapfile -t got < <(pixels t.$ext 0,0 16,16)
  [ "${got[0]}" = 4 ] || fail "transparent-$ext" "${got[0]} channels, expected 4"
  [ "${got[1]}" = "51 102 153 0" ] || fail "transparent-$ext" "corner ${got[1]}, expected the background 51 102 153 with alpha 0"
  [ "${got[2]##* }" = 255 ] || fail "transparent-$ext" "centre ${got[2]}, expected alpha 255"
done
# Without it: 3 channels.
"$RAYFORM_BIN" render tri.obj -o o.png --size 32x32 -q 2>err.log || fail opaque "exit $?: $(cat err.log)"
[ "$(pixels o.png | head -1)" = 3 ] || fail opaque "without --transparent: $(pixels o.png | head -1) channels, expected 3"
[ $failures -eq $before ] && echo "ok   [transparent] .png and .tga: 4 channels, alpha 0 on the background, 255 inside"

# With --spp 16 the sphere's edge has pixels between 0 and 255 (the fraction of samples that hit).
before=$failures
if ! "$RAYFORM_BIN" render sphere.txt -o s.png --size 32x32 --spp 16 --transparent -q 2>err.log; then
  fail edge "exit $?: $(cat err.log)"
else
  row=$(for x in $(seq 16 31); do echo "$x,16"; done)
  # shellcheck disable=SC2086  # one argument per pixel
  alphas=$(pixels s.png $row | tail -n +2 | awk '{print $4}' | tr '\n' ' ')
  awk -v a="$alphas" 'BEGIN { n = split(a, v, " "); between = 0
    if (v[1] != 255 || v[n] != 0) exit 1
    for (i = 1; i <= n; ++i) between += v[i] > 0 && v[i] < 255
    exit between == 0 }' || fail edge "alpha along the centre row from the middle: $alphas (expected 255 ... some between ... 0)"
fi
[ $failures -eq $before ] && echo "ok   [edge] --spp 16: alpha along the centre row $alphas"

# EXR (premultiplied): RGBA, the background 0, 0, 0, 0 and the centre alpha 1,
# read with oiiotool when it is installed.
if command -v oiiotool >/dev/null; then
  before=$failures
  if ! "$RAYFORM_BIN" render sphere.txt -o t.exr --size 32x32 --transparent -q 2>err.log; then
    fail exr "exit $?: $(cat err.log)"
  else
    info=$(oiiotool --info -v t.exr 2>&1)
    grep -q 'channel list: R, G, B, A' <<<"$info" || fail exr "not RGBA: $info"
    pixel() { oiiotool t.exr --cut "1x1+$1+$2" --printstats 2>&1 | grep 'Stats Max' | sed 's/.*Max: //; s/ (float)//'; }
    corner=$(pixel 0 0) centre=$(pixel 16 16)
    [ "$corner" = "0.000000 0.000000 0.000000 0.000000" ] || fail exr "corner $corner, expected 0 0 0 0"
    [ "${centre##* }" = "1.000000" ] || fail exr "centre $centre, expected alpha 1"
  fi
  [ $failures -eq $before ] && echo "ok   [exr] RGBA, the background 0 0 0 0 (premultiplied), the centre alpha 1"
fi

if [ $failures -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all background and alpha checks passed"
