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
  materials.obj, materials.mtl
                OBJ test asset (tests/scripts/asset_golden.sh): four materials
                (checker.bmp and uvgrid.bmp textures, a specular red, a blue),
                uvs, a box written with negative (relative) indices and a
                pyramid group without normals; faces +z (no camera, no light)
  features.gltf, features.bin, features_grid.png, features_holes.png,
  features.glb  glTF 2.0 test asset, .gltf + .bin + .png and the same as one
                self-contained .glb: node hierarchy with TRS and matrix nodes,
                a textured floor (NEAREST/REPEAT sampler, KHR_texture_transform),
                a cube with vertex colours (COLOR_0), an alphaMode MASK fence
                cut out by the texture's alpha, a perspective camera and
                KHR_lights_punctual directional, point and spot lights

Everything is computed here (no third-party data); the output is
deterministic, so re-running it must leave the committed files unchanged.
Python 3 standard library only.
"""
import json
import math
import os
import struct
import sys
import zlib


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


def write_png(path, width, height, channels, pixel):
    """8-bit PNG (RGB or RGBA); pixel(x, y) -> tuple of `channels` bytes, y = 0 the TOP row."""
    with open(path, 'wb') as f:
        f.write(png_bytes(width, height, channels, pixel))


def png_bytes(width, height, channels, pixel):
    raw = bytearray()
    for y in range(height):
        raw.append(0)  # filter: none
        for x in range(width):
            raw += bytes(pixel(x, y))
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    colour_type = {3: 2, 4: 6}[channels]
    ihdr = struct.pack('>IIBBBBB', width, height, 8, colour_type, 0, 0, 0)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', zlib.compress(bytes(raw), 9)) +
            chunk(b'IEND', b''))


# ---- OBJ test asset -------------------------------------------------------------------

def materials_obj(out):
    gen = 'generated by tests/tools/make_scene_assets.py'
    mtl = [
        '# materials of materials.obj; ' + gen,
        'newmtl checker', 'Kd 1 1 1', 'Ks 0 0 0', 'map_Kd checker.bmp', '',
        'newmtl uvgrid', 'Kd 1 1 1', 'Ks 0 0 0', 'map_Kd uvgrid.bmp', '',
        'newmtl red', 'Kd 0.8 0.15 0.1', 'Ks 0.5 0.5 0.5', 'Ns 60', '',
        'newmtl blue', 'Kd 0.2 0.35 0.85', 'Ks 0 0 0', '',
    ]
    with open(os.path.join(out, 'materials.mtl'), 'w', newline='\n') as f:
        f.write('\n'.join(mtl))
    L = ['# OBJ test asset: materials, uvs, textures, negative indices, a group without normals',
         '# ' + gen, 'mtllib materials.mtl']
    # Laid out facing +z, so that the camera and head-light rayform adds to a
    # file without them (looking down -z at the bounds) light every part.
    # Backdrop: 4x4 quad at z = -1, uvs 0..2 (the checker repeats twice), one normal.
    L += ['o backdrop',
          'v -2 -2 -1', 'v 2 -2 -1', 'v 2 2 -1', 'v -2 2 -1',
          'vt 0 0', 'vt 2 0', 'vt 2 2', 'vt 0 2', 'vn 0 0 1',
          'usemtl checker', 'f 1/1/1 2/2/1 3/3/1 4/4/1']
    # Sign: quad in front of it showing uvgrid.bmp the right way up (v = 1 at its top).
    L += ['o sign',
          'v -1.7 0.3 -0.6', 'v -0.3 0.3 -0.6', 'v -0.3 1.7 -0.6', 'v -1.7 1.7 -0.6',
          'vt 0 0', 'vt 1 0', 'vt 1 1', 'vt 0 1', 'vn 0 0 1',
          'usemtl uvgrid', 'f 5/5/2 6/6/2 7/7/2', 'f 5/5/2 7/7/2 8/8/2']
    # Box: side 1, turned 35 degrees about y then 25 about x, centred at (0.8, -0.3, -0.2);
    # every reference negative (relative to the end of the lists so far).
    ay, ax = math.radians(35), math.radians(25)
    def turn(p):
        x, y, z = p
        x, z = x * math.cos(ay) + z * math.sin(ay), -x * math.sin(ay) + z * math.cos(ay)
        y, z = y * math.cos(ax) - z * math.sin(ax), y * math.sin(ax) + z * math.cos(ax)
        return (x, y, z)
    c, h = (0.8, -0.3, -0.2), 0.5
    L += ['o box']
    corners = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
    L += ['v %s %s %s' % tuple(fmt(c[k] + h * turn(p)[k]) for k in range(3)) for p in corners]
    normals = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    L += ['vn %s %s %s' % tuple(fmt(v) for v in turn(n)) for n in normals]
    idx = lambda x, y, z: (1 if z > 0 else 0) * 4 + (1 if y > 0 else 0) * 2 + (1 if x > 0 else 0)
    quads = [  # counter-clockwise from outside, with their normal's index
        ([(1, -1, 1), (1, -1, -1), (1, 1, -1), (1, 1, 1)], 0),
        ([(-1, -1, -1), (-1, -1, 1), (-1, 1, 1), (-1, 1, -1)], 1),
        ([(-1, 1, 1), (1, 1, 1), (1, 1, -1), (-1, 1, -1)], 2),
        ([(-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1)], 3),
        ([(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], 4),
        ([(1, -1, -1), (-1, -1, -1), (-1, 1, -1), (1, 1, -1)], 5),
    ]
    L += ['usemtl red']
    for q, n in quads:
        L.append('f ' + ' '.join('%d//%d' % (idx(*p) - 8, n - 6) for p in q))
    # Pyramid pointing at the viewer: a group with positions only (no uvs, no
    # normals), so its normals are computed (smooth by default, --flat: faceted).
    L += ['g pyramid', 'usemtl blue',
          'v -1.5 -1.6 -0.95', 'v -0.3 -1.6 -0.95', 'v -0.3 -0.4 -0.95', 'v -1.5 -0.4 -0.95', 'v -0.9 -1.0 0.1',
          'f 17 18 21', 'f 18 19 21', 'f 19 20 21', 'f 20 17 21', 'f 17 20 19 18']
    with open(os.path.join(out, 'materials.obj'), 'w', newline='\n') as f:
        f.write('\n'.join(L) + '\n')


# ---- glTF test asset ------------------------------------------------------------------

def quat_axis_angle(axis, deg):
    a = math.radians(deg) / 2
    n = math.sqrt(sum(c * c for c in axis))
    return [axis[0] / n * math.sin(a), axis[1] / n * math.sin(a), axis[2] / n * math.sin(a), math.cos(a)]


def quat_mul(q, r):
    x1, y1, z1, w1 = q
    x2, y2, z2, w2 = r
    return [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]


def quat_looking(direction):
    """Rotation taking local -z to `direction` (yaw about y, then pitch about x)."""
    dx, dy, dz = direction
    yaw = math.degrees(math.atan2(-dx, -dz))
    pitch = math.degrees(math.atan2(dy, math.hypot(dx, dz)))
    return quat_mul(quat_axis_angle((0, 1, 0), yaw), quat_axis_angle((1, 0, 0), pitch))


def rounded(v, digits=6):
    if isinstance(v, list):
        return [rounded(c, digits) for c in v]
    r = round(v, digits)
    return 0.0 if r == 0 else r


def features_grid(x, y):
    """32x32: 4x4 cells of two blues, an orange mark in the cell at u ~ 0, v ~ 0 (bottom left)."""
    if x < 8 and y >= 24 and x + (31 - y) < 10:
        return (250, 140, 20)
    return (40, 90, 200) if ((x // 8) + (y // 8)) % 2 == 0 else (225, 230, 240)


def features_holes(x, y):
    """64x64 RGBA: a green lattice, transparent round holes (alpha 0) between its bars."""
    cx, cy = (x % 16) - 7.5, (y % 16) - 7.5
    if cx * cx + cy * cy < 5.5 * 5.5:
        return (255, 0, 255, 0)  # magenta where cut out: must never show
    return (60, 170, 70, 255)


def features_gltf(out):
    bin_ = bytearray()
    views, accessors = [], []

    def add(data, fmt_char, count, type_, component, target=None, minmax=None):
        while len(bin_) % 4:
            bin_.append(0)
        at = len(bin_)
        bin_.extend(struct.pack('<%d%s' % (len(data), fmt_char), *data))
        view = {'buffer': 0, 'byteOffset': at, 'byteLength': len(bin_) - at}
        if target:
            view['target'] = target
        views.append(view)
        acc = {'bufferView': len(views) - 1, 'componentType': component, 'count': count, 'type': type_}
        if minmax:
            acc['min'], acc['max'] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    def mesh_accessors(pos, nrm=None, uv=None, col=None, idx=None):
        flat = lambda vs: [c for v in vs for c in v]
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        attrs = {'POSITION': add(flat(pos), 'f', len(pos), 'VEC3', 5126, 34962, (lo, hi))}
        if nrm:
            attrs['NORMAL'] = add(flat(nrm), 'f', len(nrm), 'VEC3', 5126, 34962)
        if uv:
            attrs['TEXCOORD_0'] = add(flat(uv), 'f', len(uv), 'VEC2', 5126, 34962)
        if col:
            attrs['COLOR_0'] = add(flat(col), 'f', len(col), 'VEC3', 5126, 34962)
        indices = add(idx, 'H', len(idx), 'SCALAR', 5123, 34963)
        return attrs, indices

    meshes = []
    # Floor: [-1,1]^2 at y = 0, uvs (0,0) at the far left corner (glTF: v down).
    a, i = mesh_accessors([(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], [(0, 1, 0)] * 4,
                          [(0, 0), (0, 1), (1, 1), (1, 0)], None, [0, 1, 2, 0, 2, 3])
    meshes.append({'name': 'floor', 'primitives': [{'attributes': a, 'indices': i, 'material': 0}]})
    # Cube [-0.5,0.5]^3, one colour per face (COLOR_0).
    pos, nrm, col, idx = [], [], [], []
    faces = [((1, 0, 0), (0.9, 0.2, 0.2)), ((-1, 0, 0), (0.2, 0.8, 0.3)), ((0, 1, 0), (0.95, 0.85, 0.2)),
             ((0, -1, 0), (0.5, 0.5, 0.5)), ((0, 0, 1), (0.25, 0.4, 0.95)), ((0, 0, -1), (0.8, 0.3, 0.8))]
    for n, c in faces:
        k = [j for j in range(3) if n[j] != 0][0]
        u_axis = [0, 0, 0]; u_axis[(k + 1) % 3] = 1
        v_axis = [0, 0, 0]; v_axis[(k + 2) % 3] = 1
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(0.5 * n[j] + 0.5 * su * u_axis[j] + 0.5 * sv * v_axis[j] for j in range(3)))
            nrm.append(n)
            col.append(c)
        # u x v = +axis: counter-clockwise seen from outside for positive faces; flip for negative.
        tri = [0, 1, 2, 0, 2, 3] if sum(n) > 0 else [0, 2, 1, 0, 3, 2]
        idx += [base + t for t in tri]
    a, i = mesh_accessors(pos, nrm, None, col, idx)
    meshes.append({'name': 'cube', 'primitives': [{'attributes': a, 'indices': i, 'material': 1}]})
    # Fence: [-0.5,0.5]^2 upright quad facing +z, the whole texture on it.
    a, i = mesh_accessors([(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)], [(0, 0, 1)] * 4,
                          [(0, 1), (1, 1), (1, 0), (0, 0)], None, [0, 1, 2, 0, 2, 3])
    meshes.append({'name': 'fence', 'primitives': [{'attributes': a, 'indices': i, 'material': 2}]})
    geometry_bytes = len(bin_)

    materials = [
        {'name': 'grid floor', 'pbrMetallicRoughness': {
            'baseColorTexture': {'index': 0, 'extensions': {'KHR_texture_transform': {
                'offset': [0.25, 0.0], 'rotation': 0.3, 'scale': [3.0, 3.0]}}},
            'metallicFactor': 0.0, 'roughnessFactor': 1.0}},
        {'name': 'vertex colours', 'pbrMetallicRoughness': {
            'baseColorFactor': [1.0, 1.0, 1.0, 1.0], 'metallicFactor': 0.0, 'roughnessFactor': 0.5}},
        {'name': 'fence cut-out', 'alphaMode': 'MASK', 'alphaCutoff': 0.5, 'doubleSided': True,
         'pbrMetallicRoughness': {'baseColorTexture': {'index': 1}, 'metallicFactor': 0.0, 'roughnessFactor': 1.0}},
    ]
    cam_pos, cam_target = (1.0, 2.5, 4.4), (0.0, 0.35, 0.0)
    d = [cam_target[k] - cam_pos[k] for k in range(3)]
    spot_pos, spot_target = (-2.0, 2.5, 2.0), (-1.1, 0.0, 1.2)
    sd = [spot_target[k] - spot_pos[k] for k in range(3)]
    ang = math.radians(35)
    root_matrix = [math.cos(ang), 0, -math.sin(ang), 0, 0, 1, 0, 0, math.sin(ang), 0, math.cos(ang), 0, 0, 0, 0, 1]
    cube_ang = math.radians(40)
    cube_matrix = [math.cos(cube_ang), 0, -math.sin(cube_ang), 0, 0, 1, 0, 0, math.sin(cube_ang), 0, math.cos(cube_ang), 0,
                   -0.5, 0.5, 0.1, 1]
    nodes = [
        {'name': 'root (matrix: 35 degrees about y)', 'matrix': root_matrix, 'children': [1, 2]},
        {'name': 'floor (TRS)', 'mesh': 0, 'translation': [0, 0, 0], 'rotation': quat_axis_angle((0, 1, 0), -35),
         'scale': [2.0, 1.0, 2.0]},
        {'name': 'group (TRS)', 'translation': [0.1, 0.0, 0.0], 'rotation': quat_axis_angle((0, 1, 0), -35),
         'scale': [1.0, 1.0, 1.0], 'children': [3, 4]},
        {'name': 'cube (matrix)', 'mesh': 1, 'matrix': cube_matrix},
        {'name': 'fence (TRS)', 'mesh': 2, 'translation': [0.7, 0.65, 0.2],
         'rotation': quat_axis_angle((0, 1, 0), -25), 'scale': [1.2, 1.2, 1.2]},
        {'name': 'camera', 'camera': 0, 'translation': list(cam_pos), 'rotation': quat_looking(d)},
        {'name': 'sun', 'rotation': quat_looking((-0.4, -1.0, -0.7)),
         'extensions': {'KHR_lights_punctual': {'light': 0}}},
        {'name': 'lamp', 'translation': [1.6, 1.8, 1.4], 'extensions': {'KHR_lights_punctual': {'light': 1}}},
        {'name': 'spot', 'translation': list(spot_pos), 'rotation': quat_looking(sd),
         'extensions': {'KHR_lights_punctual': {'light': 2}}},
    ]
    for n in nodes:
        for k in ('matrix', 'rotation', 'translation', 'scale'):
            if k in n:
                n[k] = rounded([float(c) for c in n[k]], 7)
    lights = [
        {'name': 'sun', 'type': 'directional', 'color': [1.0, 0.96, 0.9], 'intensity': 0.8},
        {'name': 'lamp', 'type': 'point', 'color': [1.0, 0.9, 0.7], 'intensity': 2.5},
        {'name': 'spot', 'type': 'spot', 'color': [0.6, 0.8, 1.0], 'intensity': 8.0,
         'spot': {'innerConeAngle': 0.25, 'outerConeAngle': 0.45}},
    ]
    grid = png_bytes(32, 32, 3, features_grid)
    holes = png_bytes(64, 64, 4, features_holes)
    doc = {
        'asset': {'version': '2.0', 'generator': 'tests/tools/make_scene_assets.py'},
        'extensionsUsed': ['KHR_texture_transform', 'KHR_lights_punctual'],
        'extensions': {'KHR_lights_punctual': {'lights': lights}},
        'scene': 0,
        'scenes': [{'nodes': [0, 5, 6, 7, 8]}],
        'nodes': nodes,
        'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.75, 'aspectRatio': 1.0, 'znear': 0.1, 'zfar': 100.0}}],
        'meshes': meshes,
        'materials': materials,
        'samplers': [{'magFilter': 9728, 'minFilter': 9728, 'wrapS': 10497, 'wrapT': 10497},
                     {'magFilter': 9729, 'minFilter': 9729, 'wrapS': 33071, 'wrapT': 33071}],
        'textures': [{'sampler': 0, 'source': 0}, {'sampler': 1, 'source': 1}],
        'accessors': accessors,
    }
    # .gltf: external .bin and .png files.
    with open(os.path.join(out, 'features_grid.png'), 'wb') as f:
        f.write(grid)
    with open(os.path.join(out, 'features_holes.png'), 'wb') as f:
        f.write(holes)
    with open(os.path.join(out, 'features.bin'), 'wb') as f:
        f.write(bytes(bin_))
    text = dict(doc, bufferViews=views, buffers=[{'uri': 'features.bin', 'byteLength': geometry_bytes}],
                images=[{'uri': 'features_grid.png'}, {'uri': 'features_holes.png'}])
    with open(os.path.join(out, 'features.gltf'), 'w', newline='\n') as f:
        f.write(json.dumps(text, indent=1) + '\n')
    # .glb: the same, the images in the binary chunk.
    glb_bin = bytearray(bin_)
    glb_views = list(views)
    images = []
    for data in (grid, holes):
        while len(glb_bin) % 4:
            glb_bin.append(0)
        glb_views.append({'buffer': 0, 'byteOffset': len(glb_bin), 'byteLength': len(data)})
        glb_bin.extend(data)
        images.append({'bufferView': len(glb_views) - 1, 'mimeType': 'image/png'})
    while len(glb_bin) % 4:
        glb_bin.append(0)
    binary = dict(doc, bufferViews=glb_views, buffers=[{'byteLength': len(glb_bin)}], images=images)
    js = json.dumps(binary, separators=(',', ':')).encode()
    js += b' ' * (-len(js) % 4)
    total = 12 + 8 + len(js) + 8 + len(glb_bin)
    with open(os.path.join(out, 'features.glb'), 'wb') as f:
        f.write(struct.pack('<4sII', b'glTF', 2, total))
        f.write(struct.pack('<I4s', len(js), b'JSON') + js)
        f.write(struct.pack('<I4s', len(glb_bin), b'BIN\0') + bytes(glb_bin))


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
    materials_obj(out)
    features_gltf(out)
    print('wrote assets into', os.path.normpath(out))


if __name__ == '__main__':
    main()
