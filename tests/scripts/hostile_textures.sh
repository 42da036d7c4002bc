#!/usr/bin/env bash
# Hostile textures (issue 33): sizes read against the format's own end, a
# memory budget for the whole job, and headers that declare more texels than
# their data can hold. Each file is made here; each case must end at once
# with exit 0 and the right output, or exit 1 and one line.
#  - an 8x8 PNG followed by 200 MB of zeros (sparse): render reads to IEND,
#    convert copies the PNG without the zeros and says so;
#  - three 260 kB palette PNGs of 16384x16384 (deflate's ratio, each within
#    the texel limit): refused by --limit memory=1G before one is decoded;
#  - a float RGB TIFF of 8192x8192 (zip, ~0.9 MB; needs oiiotool): refused
#    by the memory limit before OpenImageIO decodes it;
#  - a 70-byte lossless WebP declaring 16384x16384, and a PNG declaring
#    16384x16384 RGB over 1 kB of data: refused before decoding.
# Needs python3 (standard library only); no third-party data.
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
failures=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

python3 - <<'PY' || { echo "FAIL: could not make the files"; exit 1; }
import struct, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
def png(w, h, ctype, idat, plte=None):
    s = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, ctype, 0, 0, 0))
    if plte: s += chunk(b'PLTE', plte)
    return s + chunk(b'IDAT', idat) + chunk(b'IEND', b'')
rows = b''.join(b'\x00' + b'\xff\x00\x00' * 8 for _ in range(8))  # 8x8 red
open('small.png', 'wb').write(png(8, 8, 2, zlib.compress(rows)))
co = zlib.compressobj(9)
row = b'\x00' * 16385
big = png(16384, 16384, 3, b''.join(co.compress(row) for _ in range(16384)) + co.flush(), b'\x80\x40\x20')
for i in (1, 2, 3): open('big%d.png' % i, 'wb').write(big)
open('short.png', 'wb').write(png(16384, 16384, 2, zlib.compress(b'\x00' * 100000)))
bits = (16384 - 1) | (16384 - 1) << 14
vp8l = b'\x2f' + struct.pack('<I', bits)
vp8l += b'\x00' * (50 - len(vp8l))
body = b'WEBP' + b'VP8L' + struct.pack('<I', len(vp8l)) + vp8l
open('header.webp', 'wb').write(b'RIFF' + struct.pack('<I', len(body)) + body)
PY
cp small.png trailing.png && truncate -s +200M trailing.png

# scene NAME TEXTURE...: an OBJ of one triangle a texture.
scene() {
  local name=$1 i=0; shift
  { echo "mtllib $name.mtl"; echo "v -1 -1 0"; echo "v 1 -1 0"; echo "v 1 1 0"; echo "vt 0 0"; echo "vt 1 0"; echo "vt 1 1"
    for t in "$@"; do echo "usemtl m$i"; echo "f 1/1 2/2 3/3"; i=$((i + 1)); done; } >"$name.obj"
  i=0; for t in "$@"; do printf 'newmtl m%d\nKd 1 1 1\nmap_Kd %s\n' $i "$t"; i=$((i + 1)); done >"$name.mtl"
}
# refused NAME REGEX ARGS...: rayform ARGS exits 1 with one line matching REGEX, within 10 s.
refused() {
  local name=$1 pattern=$2; shift 2
  timeout 10 "$RAYFORM_BIN" -q "$@" >stdout 2>stderr; local rc=$?
  [ $rc -eq 1 ] || fail "$name" "exit status $rc, expected 1 (stderr: $(head -c 300 stderr))"
  [ "$(wc -l <stderr)" -eq 1 ] || fail "$name" "expected one line, got: $(cat stderr)"
  grep -Eq "$pattern" stderr || fail "$name" "expected /$pattern/, got: $(cat stderr)"
}

scene trailing trailing.png
timeout 10 "$RAYFORM_BIN" render trailing.obj -o trailing_out.png --size 16x16 >/dev/null 2>stderr \
  || fail trailing-render "exit $? ($(cat stderr))"
timeout 10 "$RAYFORM_BIN" convert trailing.obj trailing.glb >/dev/null 2>stderr || fail trailing-convert "exit $? ($(cat stderr))"
size=$(stat -c %s trailing.glb 2>/dev/null || echo 0)
[ "$size" -gt 0 ] && [ "$size" -lt 100000 ] || fail trailing-convert "trailing.glb is $size bytes, expected the 8x8 PNG (< 100 kB)"
grep -q "texture 'trailing.png': 209715200 bytes after the PNG image's end (IEND) are ignored" stderr \
  || fail trailing-convert "expected the note on the ignored bytes, got: $(cat stderr)"

scene three big1.png big2.png big3.png
refused three-bombs "big[123]\.png: decoding the 16384x16384 texture \(and keeping it as 1\.07 GB\) needs 1\.88 GB, more than the .*memory limit of 1\.00 GB \(raise it with --limit memory=N\)$" \
  render three.obj -o three.png --size 16x16 --limit memory=1G
[ -e three.png ] && fail three-bombs "three.png written"

if command -v oiiotool >/dev/null; then
  oiiotool --pattern constant:color=0.5,0.4,0.3 8192x8192 3 -d float --compression zip -o float.tif
  scene float float.tif
  refused float-tiff "float\.tif: decoding the 8192x8192 texture needs 1\.61 GB, more than the .*memory limit of 1\.00 GB" \
    render float.obj -o float.png --size 16x16 --limit memory=1G
fi

scene webp header.webp
refused webp-header "header\.webp: cannot decode image: the header declares 16384x16384 texels, more than its 70 bytes can hold" \
  render webp.obj -o webp.png --size 16x16
scene short short.png
refused png-header "short\.png: cannot decode image: the header declares 16384x16384 texels \(805306368 bytes of rows\), more than its [0-9]+ bytes of compressed data can hold" \
  render short.obj -o short_out.png --size 16x16

# --help names the limit and its default.
"$RAYFORM_BIN" render --help | tr -s ' \n' ' ' | grep -Eq "json-depth, memory;.* memory [0-9.]+ [kMG]B \(bytes the job may hold at once" \
  || fail help "rayform render --help does not name the memory limit and its default"

[ $failures -eq 0 ] && echo "PASS: hostile textures" || { echo "$failures failure(s)"; exit 1; }
