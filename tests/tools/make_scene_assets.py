#!/usr/bin/env python3
"""Generates the meshes and textures of our own course-format scenes.

Writes into scenes/assets/ (or the folder given as the only argument):
  checker.bmp   128x128 checkerboard, 8x8 squares, two warm colours
  uvgrid.bmp    64x64 orientation texture: red grows with u, green with v
                (v = 1 is the TOP row of the picture), a white square marks
                the corner u = 0, v = 1 and a blue cross the centre
  stripes.bmp   64x16 diagonal stripes
  torus.obj     torus (R = 1, r = 0.4) with uvs; positions are shared across
                the uv seam so that the course's computed normals stay smooth
  tile.obj      [-1,1]^2 quad in z = 0, 4x4 cells, uvs from (0,0) to (1,1)
  box.obj       [-1,1]^3 box, 8 shared positions, each face mapped to the
                whole texture (24 corners), quads as polygons

Everything is computed here (no third-party data); the output is
deterministic, so re-running it must leave the committed files unchanged.
Python 3 standard library only.
"""
import math
import os
import struct
import sys


def write_bmp(path, width, height, pixel):
    """24-bit BMP; pixel(x, y) -> (r, g, b) bytes with y = 0 the TOP row."""
    row_bytes = (3 * width + 3) & ~3
    image_size = row_bytes * height
    header = struct.pack('<2sIHHI', b'BM', 14 + 40 + image_size, 0, 0, 14 + 40)
    info = struct.pack('<IiiHHIIiiII', 40, width, height, 1, 24, 0, image_size, 2835, 2835, 0, 0)
    rows = []
    for y in range(height - 1, -1, -1):  # BMP rows are stored bottom-up
        row = bytearray()
        for x in range(width):
            r, g, b = pixel(x, y)
            row += bytes((b, g, r))
        row += b'\0' * (row_bytes - 3 * width)
        rows.append(bytes(row))
    with open(path, 'wb') as f:
        f.write(header + info + b''.join(rows))


def checker(x, y):
    if ((x // 16) + (y // 16)) % 2 == 0:
        return (236, 224, 196)
    return (176, 68, 46)


def uvgrid(x, y):
    w = h = 64
    if x < 12 and y < 12:  # u ~ 0, v ~ 1: top-left corner
        return (255, 255, 255)
    if abs(x - 31.5) < 2 or abs(y - 31.5) < 2:
        if abs(x - 31.5) < 10 and abs(y - 31.5) < 10:
            return (40, 60, 255)
    r = round(255 * x / (w - 1))
    g = round(255 * (h - 1 - y) / (h - 1))
    grid = 0 if (x % 8 == 0 or y % 8 == 0) else 40
    return (r, g, 30 + grid)


def stripes(x, y):
    return (250, 200, 40) if ((x + y) // 4) % 2 == 0 else (30, 110, 170)


def fmt(v):
    """Six significant digits; -0 written as 0."""
    s = '%.6g' % v
    return '0' if s == '-0' else s


def write_obj(path, comment, positions, uvs, faces):
    """faces: lists of (position index, uv index), 0-based."""
    lines = ['# ' + c for c in comment]
    lines += ['v %s %s %s' % tuple(fmt(c) for c in p) for p in positions]
    lines += ['vt %s %s' % tuple(fmt(c) for c in t) for t in uvs]
    for f in faces:
        lines.append('f ' + ' '.join('%d/%d' % (p + 1, t + 1) for p, t in f))
    with open(path, 'w', newline='\n') as out:
        out.write('\n'.join(lines) + '\n')


def torus(segments=32, rings=16, R=1.0, r=0.4):
    positions, uvs, faces = [], [], []
    for i in range(segments):          # around the main circle (u)
        a = 2 * math.pi * i / segments
        for j in range(rings):         # around the tube (v)
            b = 2 * math.pi * j / rings
            positions.append(((R + r * math.cos(b)) * math.cos(a), r * math.sin(b), -(R + r * math.cos(b)) * math.sin(a)))
    # uvs on a (segments+1) x (rings+1) grid: the seam gets its own uvs.
    for i in range(segments + 1):
        for j in range(rings + 1):
            uvs.append((i / segments, j / rings))
    P = lambda i, j: (i % segments) * rings + (j % rings)
    T = lambda i, j: i * (rings + 1) + j
    for i in range(segments):
        for j in range(rings):
            a, b, c, d = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
            faces.append([(P(*a), T(*a)), (P(*b), T(*b)), (P(*c), T(*c))])
            faces.append([(P(*a), T(*a)), (P(*c), T(*c)), (P(*d), T(*d))])
    return positions, uvs, faces


def tile(n=4):
    positions, uvs, faces = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            positions.append((-1 + 2 * i / n, -1 + 2 * j / n, 0.0))
            uvs.append((i / n, j / n))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            faces.append([(a, a), (b, b), (c, c)])
            faces.append([(a, a), (c, c), (d, d)])
    return positions, uvs, faces


def box():
    positions = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
    idx = lambda x, y, z: (1 if z > 0 else 0) * 4 + (1 if y > 0 else 0) * 2 + (1 if x > 0 else 0)
    uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]
    # Each face counter-clockwise seen from outside, starting bottom-left of its picture.
    quads = [
        [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],      # +z (front)
        [(1, -1, -1), (-1, -1, -1), (-1, 1, -1), (1, 1, -1)],  # -z
        [(1, -1, 1), (1, -1, -1), (1, 1, -1), (1, 1, 1)],      # +x
        [(-1, -1, -1), (-1, -1, 1), (-1, 1, 1), (-1, 1, -1)],  # -x
        [(-1, 1, 1), (1, 1, 1), (1, 1, -1), (-1, 1, -1)],      # +y
        [(-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1)],  # -y
    ]
    faces = [[(idx(*c), k) for k, c in enumerate(q)] for q in quads]
    return positions, uvs, faces


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, '..', '..', 'scenes', 'assets')
    os.makedirs(out, exist_ok=True)
    write_bmp(os.path.join(out, 'checker.bmp'), 128, 128, checker)
    write_bmp(os.path.join(out, 'uvgrid.bmp'), 64, 64, uvgrid)
    write_bmp(os.path.join(out, 'stripes.bmp'), 64, 16, stripes)
    gen = 'generated by tests/tools/make_scene_assets.py'
    write_obj(os.path.join(out, 'torus.obj'), ['torus R=1 r=0.4, 32x16 segments, uvs', gen], *torus())
    write_obj(os.path.join(out, 'tile.obj'), ['quad [-1,1]^2 at z=0, 4x4 cells, uvs', gen], *tile())
    write_obj(os.path.join(out, 'box.obj'), ['box [-1,1]^3, one picture per face, quads', gen], *box())
    print('wrote assets into', os.path.normpath(out))


if __name__ == '__main__':
    main()
