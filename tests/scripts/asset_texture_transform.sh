#!/usr/bin/env bash
# KHR_texture_transform: renders the glTF sample TextureTransformTest.gltf
# (no camera in the file: an explicit one looking down -z at its six squares)
# and checks the albedo picture (no lighting) at a grid of points on every
# square (Offset U, Offset V, Offset UV, Rotation, Scale, All; the clamp
# sampler decides what Rotation, Scale and All show outside [0,1]) and on the
# marker squares (Correct, NotSupported, Error textures).
#
# The expected colours are derived here, independently of rayform: a small
# python3 (standard library only) PNG decoder reads the textures, each pixel's
# point on the z = 0/0.01 squares comes from the pinhole camera, the uvs from
# the file's vertices (UV0 or UV1), the transform from the extension's
# formula (uv' = T R S uv, R = [[cos r, sin r], [-sin r, cos r]]), the texel
# from the sampler (CLAMP_TO_EDGE or REPEAT, nearest texel). Only points whose
# neighbourhood (2 texels and 2 pixels around, 2 pixels from any square's edge) has one
# colour are checked, so filtering and pixel-centre conventions do not matter;
# each must match within 3/255. Every square must contribute at least 20 points
# of at least two colours (the black arrow among them on Rotation, Scale and
# All), every Correct marker at least 3 (the NotSupported and Error markers,
# 16 pixels wide and mostly covered by their symbol, are checked where they can be).
source "$(dirname "$0")/lib.sh"
require_shared
gltf="$RAYFORM_SHARED/assets/gltf/textureTransform/TextureTransformTest.gltf"
[ -f "$gltf" ] || { echo "FAIL: $gltf missing"; exit 1; }
command -v python3 >/dev/null || { echo "FAIL: python3 not found"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
W=400; FOV=40; DIST=5
if ! "$RAYFORM_BIN" render "$gltf" -o "$tmp/c.png" --albedo "$tmp/albedo.png" --size ${W}x${W} \
     --look-from 0,0,$DIST --look-at 0,0,0 --up 0,1,0 --fov $FOV -q >"$tmp/log" 2>&1; then
  echo "FAIL: rayform failed: $(cat "$tmp/log")"; exit 1
fi
python3 - "$gltf" "$tmp/albedo.png" $W $FOV $DIST <<'EOF'
import json, math, os, struct, sys, zlib

def read_png(path):
    """8-bit, non-interlaced grey/RGB/RGBA PNG -> (w, h, channels, rows of bytes)."""
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', path
    at, idat, ihdr = 8, b'', None
    while at < len(data):
        n, kind = struct.unpack('>I4s', data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b'IHDR': ihdr = struct.unpack('>IIBBBBB', body)
        elif kind == b'IDAT': idat += body
        at += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    assert depth == 8 and interlace == 0 and ctype in (0, 2, 4, 6), (path, ihdr)
    ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw, stride, rows, prev = zlib.decompress(idat), w * ch, [], bytearray(w * ch)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], (prev[i - ch] if i >= ch else 0)
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line); prev = line
    return w, h, ch, rows

gltf_path, albedo_path, W, FOV, DIST = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
d = json.load(open(gltf_path))
folder = os.path.dirname(gltf_path)
bin_ = open(os.path.join(folder, d['buffers'][0]['uri']), 'rb').read()
def accessor(i):
    a = d['accessors'][i]; v = d['bufferViews'][a['bufferView']]
    n = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3}[a['type']]; f = {5126: 'f', 5125: 'I'}[a['componentType']]
    at = v.get('byteOffset', 0) + a.get('byteOffset', 0)
    flat = struct.unpack_from('<%d%s' % (a['count'] * n, f), bin_, at)
    return [flat[k * n:(k + 1) * n] for k in range(a['count'])]

textures = []
for t in d['textures']:
    w, h, ch, rows = read_png(os.path.join(folder, d['images'][t['source']]['uri']))
    s = d['samplers'][t['sampler']] if 'sampler' in t else {}
    textures.append((w, h, ch, rows, s.get('wrapS', 10497), s.get('wrapT', 10497)))

def texel(ti, u, v):
    w, h, ch, rows, ws, wt = textures[ti]
    def wrap(x, mode, n):
        if mode == 33071: return min(max(int(math.floor(x * n)), 0), n - 1)   # CLAMP_TO_EDGE
        assert mode == 10497; return int(math.floor(x * n)) % n                # REPEAT
    x, y = wrap(u, ws, w), wrap(v, wt, h)  # glTF: v = 0 is the top row
    px = rows[y][x * ch:(x + 1) * ch]
    return tuple(px[:3]) if ch >= 3 else (px[0],) * 3

# Squares: nodes with a mesh, translation + scale only (the file has no rotations), under their parents.
squares = []
def walk(i, t, s):
    n = d['nodes'][i]
    assert 'rotation' not in n and 'matrix' not in n
    ns = n.get('scale', [1, 1, 1]); nt = n.get('translation', [0, 0, 0])
    t2 = [t[k] + s[k] * nt[k] for k in range(3)]; s2 = [s[k] * ns[k] for k in range(3)]
    if 'mesh' in n:
        prim = d['meshes'][n['mesh']]['primitives'][0]
        pos, uvs = accessor(prim['attributes']['POSITION']), accessor(prim['attributes']['TEXCOORD_0'])
        mat = d['materials'][prim['material']]
        info = mat['pbrMetallicRoughness']['baseColorTexture']
        tr = info.get('extensions', {}).get('KHR_texture_transform', {})
        squares.append(dict(name=n['name'], material=mat['name'], t=t2, s=s2, pos=pos, uvs=uvs,
                            tex=info['index'], transform=tr))
    for c in n.get('children', []): walk(c, t2, s2)
for r in d['scenes'][d.get('scene', 0)]['nodes']: walk(r, [0, 0, 0], [1, 1, 1])

def local_uv(sq, lx, ly):
    # The square's corners: positions (+-0.5, +-0.5, 0); uv bilinear over them (it is affine here).
    p, t = sq['pos'], sq['uvs']
    x0, x1 = min(q[0] for q in p), max(q[0] for q in p); y0, y1 = min(q[1] for q in p), max(q[1] for q in p)
    def corner(cx, cy): return t[[k for k, q in enumerate(p) if q[0] == cx and q[1] == cy][0]]
    a, b = (lx - x0) / (x1 - x0), (ly - y0) / (y1 - y0)
    c00, c10, c01, c11 = corner(x0, y0), corner(x1, y0), corner(x0, y1), corner(x1, y1)
    return tuple((1 - a) * (1 - b) * c00[k] + a * (1 - b) * c10[k] + (1 - a) * b * c01[k] + a * b * c11[k] for k in range(2))

def transform(tr, u, v):
    o, r, s = tr.get('offset', [0, 0]), tr.get('rotation', 0.0), tr.get('scale', [1, 1])
    su, sv = u * s[0], v * s[1]
    return math.cos(r) * su + math.sin(r) * sv + o[0], -math.sin(r) * su + math.cos(r) * sv + o[1]

def hit(wx, wy):
    """Front-most square at world (wx, wy) seen from +z: (square, local x, local y) or None."""
    best = None
    for sq in squares:
        lx, ly = (wx - sq['t'][0]) / sq['s'][0], (wy - sq['t'][1]) / sq['s'][1]
        if abs(lx) <= 0.5 and abs(ly) <= 0.5 and (best is None or sq['t'][2] > best[0]['t'][2]):
            best = (sq, lx, ly)
    return best

w_, h_, ch_, out = read_png(albedo_path)
assert (w_, h_) == (W, W)
half = DIST * math.tan(math.radians(FOV) / 2)   # half the view's width at z = 0
pix = 2 * half / W                               # one pixel, in world units at z = 0 (markers at 0.01: ~same)
def pixel_of(wx, wy):
    return int(math.floor((wx / half + 1) / 2 * W)), int(math.floor((1 - wy / half) / 2 * W))

tol, failures, report = 3, 0, {}
for sq in squares:
    grid = [k / 20 for k in range(-9, 10)]
    tw, th = textures[sq['tex']][0], textures[sq['tex']][1]
    colours, checked = set(), 0
    for gy in grid:
        for gx in grid:
            wx, wy = sq['t'][0] + sq['s'][0] * gx, sq['t'][1] + sq['s'][1] * gy
            # Pixel centre nearest to the point; then its own world point.
            px, py = pixel_of(wx, wy)
            cx, cy = (px + 0.5) / W * 2 * half - half, half - (py + 0.5) / W * 2 * half
            h = hit(cx, cy)
            if h is None or h[0] is not sq: continue            # hidden by a marker
            # 2 pixels from any edge of any square (no edge of another square nearby either).
            if any((hh := hit(cx + dx * pix, cy + dy * pix)) is None or hh[0] is not sq
                   for dx in (-2, 0, 2) for dy in (-2, 0, 2)): continue
            u, v = local_uv(sq, h[1], h[2])
            tu, tv = transform(sq['transform'], u, v)
            want = texel(sq['tex'], tu, tv)
            # One colour over 2 texels around (in the transformed texture space) and 2 pixels around.
            ok = True
            for ex in (-2, 0, 2):
                for ey in (-2, 0, 2):
                    if texel(sq['tex'], tu + ex / tw, tv + ey / th) != want: ok = False
                    hh = hit(cx + ex * pix, cy + ey * pix)
                    uu, vv = local_uv(sq, hh[1], hh[2])
                    if texel(sq['tex'], *transform(sq['transform'], uu, vv)) != want: ok = False
            if not ok: continue
            got = tuple(out[py][px * ch_:px * ch_ + 3])
            checked += 1; colours.add(want)
            if max(abs(got[k] - want[k]) for k in range(3)) > tol:
                failures += 1
                print('FAIL %-26s local (%+.1f, %+.1f) pixel (%d, %d) uv (%.3f, %.3f) -> (%.3f, %.3f): want %s got %s'
                      % (sq['name'], gx, gy, px, py, u, v, tu, tv, want, got))
    report.setdefault(sq['name'], (checked, colours))
    # One sample line per square, for the record: its centre.
    print('%-26s material %-13s: %2d points checked, %d colours %s' % (sq['name'], sq['material'], checked, len(colours),
          ' '.join('#%02x%02x%02x' % c for c in sorted(colours))))
for name, (checked, colours) in report.items():
    marker = ' - ' in name   # markers: small, one texture each; the squares must show their picture's structure
    arrow = name in ('Rotation', 'Scale', 'All')
    if checked < ((3 if name.endswith('Correct') else 0) if marker else 20) or len(colours) < ((1 if name.endswith('Correct') else 0) if marker else 2) or (arrow and (0, 0, 0) not in colours):
        print('FAIL %s: too few points checked (%d, %d colours)' % (name, checked, len(colours))); failures += 1
print('%d failures' % failures)
sys.exit(1 if failures else 0)
EOF
