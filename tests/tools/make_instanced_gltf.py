#!/usr/bin/env python3
"""Writes glTF 2.0 binaries (.glb) that repeat one mesh, for the instancing tests.

  make_instanced_gltf.py repeat IN OUT.glb [--count 5]
      IN (.gltf or .glb, external/embedded buffers and images) repacked as one
      self-contained .glb whose default scene holds the IN scene COUNT times:
      each copy is a new root node (translation on a grid beside the others,
      a rotation about +y and a uniform scale that differ per copy) over a
      copy of IN's node tree, and the copies share IN's meshes. Animations,
      skins and all but the first copy's cameras are dropped. This is the
      input of `gltf-transform instance` and `gltfpack -mi` (which need a mesh
      used by several nodes) in tests/scripts/asset_gltf_variants.sh.

  make_instanced_gltf.py gpu OUT.glb [--count 10000] [--mesh icosphere|box]
                         [--subdivisions N] [--seed S] [--spacing D]
                         [--uniform-scale] [--required]
                         [--single ONE.glb] [--nodes NODES.glb]
      One small mesh (an icosphere of radius 1, N subdivisions, default 2:
      320 triangles; or the [-1,1]^3 box, 12 triangles) placed COUNT times by
      EXT_mesh_gpu_instancing: one node whose
      extensions.EXT_mesh_gpu_instancing.attributes hold TRANSLATION (VEC3
      float), ROTATION (VEC4 float, unit quaternions) and SCALE (VEC3 float)
      accessors of COUNT elements. The instances lie on a square grid in the
      x-z plane (cell D, default 3) with a random height, rotation and scale
      (0.4 to 1.0 per axis, the same on all axes with --uniform-scale), from a
      fixed seed: the output is deterministic. The extension is listed in
      extensionsUsed (and in extensionsRequired with --required; without it a
      loader that ignores the extension draws the mesh once, at the node).
      --single ONE.glb: the same mesh (same buffer layout) at one plain node,
        no extension (the memory baseline of one instance).
      --nodes NODES.glb: the same COUNT placements as COUNT plain nodes that
        share the mesh, no extension (what the instanced file must render as).

Python 3 standard library only.
"""
import argparse
import base64
import copy
import json
import math
import os
import random
import struct
import sys
import urllib.parse

FLOAT, UINT16, UINT32 = 5126, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


# ---------------------------------------------------------------- GLB writing

class BinBuilder:
    """One binary buffer built from 4-byte aligned bufferViews."""

    def __init__(self, doc):
        self.doc = doc
        self.data = bytearray()
        doc.setdefault('bufferViews', [])

    def add_view(self, payload, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        view = {'buffer': 0, 'byteOffset': len(self.data), 'byteLength': len(payload)}
        if target is not None:
            view['target'] = target
        self.data += payload
        self.doc['bufferViews'].append(view)
        return len(self.doc['bufferViews']) - 1

    def add_accessor(self, fmt, values, comp, typ, count, target=None, minmax=False):
        payload = struct.pack('<' + fmt * len(values), *values)
        acc = {'bufferView': self.add_view(payload, target), 'componentType': comp,
               'count': count, 'type': typ}
        if minmax:
            n = len(values) // count
            acc['min'] = [min(values[i::n]) for i in range(n)]
            acc['max'] = [max(values[i::n]) for i in range(n)]
        self.doc.setdefault('accessors', []).append(acc)
        return len(self.doc['accessors']) - 1


def write_glb(path, doc, data):
    doc['buffers'] = [{'byteLength': len(data)}] if data else []
    js = json.dumps(doc, separators=(',', ':')).encode()
    js += b' ' * (-len(js) % 4)
    data = bytes(data) + b'\0' * (-len(data) % 4)
    chunks = struct.pack('<II', len(js), 0x4E4F534A) + js
    if data:
        chunks += struct.pack('<II', len(data), 0x004E4942) + data
    with open(path, 'wb') as f:
        f.write(struct.pack('<III', 0x46546C67, 2, 12 + len(chunks)) + chunks)


# ---------------------------------------------------------------- glTF reading

def read_gltf(path):
    """(document, [buffer bytes]) of a .gltf or .glb; external and data: URIs resolved."""
    raw = open(path, 'rb').read()
    glb_bin = None
    if raw[:4] == b'glTF':
        length = struct.unpack_from('<I', raw, 8)[0]
        at, doc = 12, None
        while at < length:
            clen, ctype = struct.unpack_from('<II', raw, at)
            body = raw[at + 8:at + 8 + clen]
            if ctype == 0x4E4F534A:
                doc = json.loads(body)
            elif ctype == 0x004E4942 and glb_bin is None:
                glb_bin = body
            at += 8 + clen
    else:
        doc = json.loads(raw)
    base = os.path.dirname(os.path.abspath(path))
    buffers = []
    for i, b in enumerate(doc.get('buffers', [])):
        buffers.append(load_uri(b['uri'], base) if 'uri' in b else glb_bin)
        if buffers[-1] is None:
            sys.exit(f'{path}: buffer {i} has no data')
    return doc, buffers, base


def load_uri(uri, base):
    if uri.startswith('data:'):
        head, _, payload = uri.partition(',')
        return base64.b64decode(payload) if head.endswith(';base64') else urllib.parse.unquote_to_bytes(payload)
    return open(os.path.join(base, urllib.parse.unquote(uri)), 'rb').read()


def mime_of(uri, data):
    if data[:8] == b'\x89PNG\r\n\x1a\n':
        return 'image/png'
    if data[:3] == b'\xff\xd8\xff':
        return 'image/jpeg'
    if data[:4] == b'RIFF' and data[8:12] == b'WEBP':
        return 'image/webp'
    ext = os.path.splitext(uri)[1].lower()
    return {'.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp',
            '.ktx2': 'image/ktx2'}.get(ext, 'application/octet-stream')


def repack(doc, buffers, base):
    """Moves every buffer and image into one binary buffer; returns its bytes."""
    out = BinBuilder({})  # only its data is used: offsets of the old buffers
    offsets = []
    for b in buffers:
        while len(out.data) % 16:
            out.data.append(0)
        offsets.append(len(out.data))
        out.data += b
    for view in doc.get('bufferViews', []):
        view['byteOffset'] = view.get('byteOffset', 0) + offsets[view['buffer']]
        view['buffer'] = 0
    for image in doc.get('images', []):
        if 'uri' in image:
            payload = load_uri(image['uri'], base)
            image['mimeType'] = mime_of(image['uri'], payload)
            del image['uri']
            while len(out.data) % 4:
                out.data.append(0)
            doc['bufferViews'].append({'buffer': 0, 'byteOffset': len(out.data), 'byteLength': len(payload)})
            out.data += payload
            image['bufferView'] = len(doc['bufferViews']) - 1
    return out.data


# ---------------------------------------------------------------- math

def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def trs_matrix(t, r, s):
    """Column-major 4x4 of T * R * S (glTF order); r = (x, y, z, w)."""
    x, y, z, w = r
    rot = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
           [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
           [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    m = [0.0] * 16
    for c in range(3):
        for row in range(3):
            m[4 * c + row] = rot[row][c] * s[c]
    m[12], m[13], m[14], m[15] = t[0], t[1], t[2], 1.0
    return m


def node_matrix(node):
    if 'matrix' in node:
        return list(node['matrix'])
    return trs_matrix(node.get('translation', (0, 0, 0)), node.get('rotation', (0, 0, 0, 1)),
                      node.get('scale', (1, 1, 1)))


def mat_mul(a, b):
    return [sum(a[4 * k + row] * b[4 * c + k] for k in range(4)) for c in range(4) for row in range(4)]


def transform_point(m, p):
    return [m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row] for row in range(3)]


def scene_bounds(doc, roots):
    """World-space box of the POSITION min/max of every mesh under `roots`."""
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    identity = [1.0 if i % 5 == 0 else 0.0 for i in range(16)]
    stack = [(n, identity) for n in roots]
    while stack:
        n, parent = stack.pop()
        node = doc['nodes'][n]
        world = mat_mul(parent, node_matrix(node))
        if 'mesh' in node:
            for prim in doc['meshes'][node['mesh']]['primitives']:
                acc = doc['accessors'][prim['attributes']['POSITION']]
                if 'min' not in acc or 'max' not in acc:
                    continue
                a, b = acc['min'], acc['max']
                for corner in range(8):
                    p = [(b if corner >> k & 1 else a)[k] for k in range(3)]
                    q = transform_point(world, p)
                    lo = [min(lo[k], q[k]) for k in range(3)]
                    hi = [max(hi[k], q[k]) for k in range(3)]
        stack += [(c, world) for c in node.get('children', [])]
    if lo[0] > hi[0]:
        sys.exit('no mesh with POSITION min/max in the scene')
    return lo, hi


# ---------------------------------------------------------------- repeat

def cmd_repeat(args):
    doc, buffers, base = read_gltf(args.input)
    data = repack(doc, buffers, base)
    scene_index = doc.get('scene', 0)
    roots = doc['scenes'][scene_index]['nodes']
    lo, hi = scene_bounds(doc, roots)
    size = max(hi[k] - lo[k] for k in range(3))
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    cols = math.ceil(math.sqrt(args.count))
    old_nodes = doc['nodes']
    doc['nodes'] = copy.deepcopy(old_nodes)  # copy 0 keeps the original indices
    new_roots = []
    for i in range(args.count):
        if i == 0:
            mapping = {n: n for n in range(len(old_nodes))}
        else:
            mapping = {}
            for n in range(len(old_nodes)):  # copies of every node; unreachable ones are harmless
                mapping[n] = len(doc['nodes'])
                doc['nodes'].append(None)
            for n, node in enumerate(old_nodes):
                c = copy.deepcopy(node)
                c.pop('camera', None)
                c.pop('skin', None)
                if 'children' in c:
                    c['children'] = [mapping[k] for k in c['children']]
                if 'name' in c:
                    c['name'] += f' (copy {i})'
                doc['nodes'][mapping[n]] = c
        angle = math.radians(37.0 * i)
        scale = 1.0 + 0.1 * (i % 3)
        gx, gz = i % cols, i // cols
        # rotate and scale about the model's centre, then move it to its cell
        rot = (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))
        rc = transform_point(trs_matrix((0, 0, 0), rot, (scale,) * 3), centre)
        t = [1.5 * size * gx - rc[0] + centre[0], 0.0, 1.5 * size * gz - rc[2] + centre[2]]
        doc['nodes'].append({'name': f'copy {i}', 'translation': t, 'rotation': list(rot),
                             'scale': [scale] * 3, 'children': [mapping[r] for r in roots]})
        new_roots.append(len(doc['nodes']) - 1)
    doc['scenes'] = [{'nodes': new_roots}]
    doc['scene'] = 0
    doc.pop('animations', None)
    doc.pop('skins', None)
    for node in doc['nodes']:
        node.pop('skin', None)
    write_glb(args.output, doc, data)
    print(f'{args.output}: {args.count} copies of {args.input} ({len(doc["nodes"])} nodes, '
          f'{len(doc.get("meshes", []))} meshes shared)')


# ---------------------------------------------------------------- gpu

def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(1 + t * t) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        cache, new_faces = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(c * c for c in p))
                verts.append(tuple(c / n for c in p))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new_faces
    return verts, list(verts), faces  # positions, normals (unit sphere), triangles


def box():
    positions, normals, faces = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = [(axis + 1) % 3, (axis + 2) % 3]
            base = len(positions)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0, 0, 0]
                p[axis], p[u], p[v] = sign, a, b
                positions.append(tuple(p))
                normals.append(tuple(n))
            if sign > 0:
                faces += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
            else:
                faces += [(base, base + 2, base + 1), (base, base + 3, base + 2)]
    return positions, normals, faces


def mesh_document(kind, subdivisions):
    positions, normals, faces = icosphere(subdivisions) if kind == 'icosphere' else box()
    doc = {'asset': {'version': '2.0', 'generator': 'rayform tests/tools/make_instanced_gltf.py'},
           'materials': [{'name': 'instanced', 'pbrMetallicRoughness': {
               'baseColorFactor': [0.8, 0.45, 0.2, 1.0], 'metallicFactor': 0.0, 'roughnessFactor': 0.8}}]}
    bb = BinBuilder(doc)
    flat = [c for p in positions for c in p]
    pos = bb.add_accessor('f', flat, FLOAT, 'VEC3', len(positions), ARRAY_BUFFER, minmax=True)
    nrm = bb.add_accessor('f', [c for n in normals for c in n], FLOAT, 'VEC3', len(normals), ARRAY_BUFFER)
    idx = bb.add_accessor('H' if len(positions) < 65536 else 'I', [i for f in faces for i in f],
                          UINT16 if len(positions) < 65536 else UINT32, 'SCALAR', 3 * len(faces),
                          ELEMENT_ARRAY_BUFFER)
    doc['meshes'] = [{'name': kind, 'primitives': [
        {'attributes': {'POSITION': pos, 'NORMAL': nrm}, 'indices': idx, 'material': 0}]}]
    return doc, bb, len(faces)


def placements(count, spacing, seed, uniform):
    rng = random.Random(seed)
    cols = math.ceil(math.sqrt(count))
    out = []
    for i in range(count):
        gx, gz = i % cols, i // cols
        t = [spacing * (gx - (cols - 1) / 2), rng.uniform(-0.5, 0.5) * spacing,
             spacing * (gz - (cols - 1) / 2)]
        # uniformly distributed unit quaternion (Shoemake)
        u1, u2, u3 = rng.random(), rng.random(), rng.random()
        q = (math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
             math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3))
        if uniform:
            s = [rng.uniform(0.4, 1.0)] * 3
        else:
            s = [rng.uniform(0.4, 1.0) for _ in range(3)]
        out.append((t, q, s))
    return out


def cmd_gpu(args):
    places = placements(args.count, args.spacing, args.seed, args.uniform_scale)

    doc, bb, tris = mesh_document(args.mesh, args.subdivisions)
    t = bb.add_accessor('f', [c for p in places for c in p[0]], FLOAT, 'VEC3', args.count, minmax=True)
    r = bb.add_accessor('f', [c for p in places for c in p[1]], FLOAT, 'VEC4', args.count)
    s = bb.add_accessor('f', [c for p in places for c in p[2]], FLOAT, 'VEC3', args.count)
    doc['nodes'] = [{'name': f'{args.count} instances', 'mesh': 0, 'extensions': {'EXT_mesh_gpu_instancing': {
        'attributes': {'TRANSLATION': t, 'ROTATION': r, 'SCALE': s}}}}]
    doc['scenes'] = [{'nodes': [0]}]
    doc['scene'] = 0
    doc['extensionsUsed'] = ['EXT_mesh_gpu_instancing']
    if args.required:
        doc['extensionsRequired'] = ['EXT_mesh_gpu_instancing']
    write_glb(args.output, doc, bb.data)
    print(f'{args.output}: {args.count} instances of a {tris}-triangle {args.mesh} (EXT_mesh_gpu_instancing)')

    if args.single:
        doc, bb, _ = mesh_document(args.mesh, args.subdivisions)
        doc['nodes'] = [{'name': 'one instance', 'mesh': 0}]
        doc['scenes'] = [{'nodes': [0]}]
        doc['scene'] = 0
        write_glb(args.single, doc, bb.data)
        print(f'{args.single}: one instance of the same mesh')

    if args.nodes:
        doc, bb, _ = mesh_document(args.mesh, args.subdivisions)
        doc['nodes'] = [{'name': f'instance {i}', 'mesh': 0, 'translation': list(p[0]), 'rotation': list(p[1]),
                         'scale': list(p[2])} for i, p in enumerate(places)]
        doc['scenes'] = [{'nodes': list(range(len(places)))}]
        doc['scene'] = 0
        write_glb(args.nodes, doc, bb.data)
        print(f'{args.nodes}: the same {args.count} placements as plain nodes')


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0],
                                     epilog=__doc__.split('\n', 2)[2], formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest='command', required=True)
    p = sub.add_parser('repeat', help='IN repacked as .glb with its scene repeated COUNT times (shared meshes)')
    p.add_argument('input')
    p.add_argument('output')
    p.add_argument('--count', type=int, default=5)
    p.set_defaults(func=cmd_repeat)
    p = sub.add_parser('gpu', help='one mesh placed COUNT times by EXT_mesh_gpu_instancing (TRS accessors)')
    p.add_argument('output')
    p.add_argument('--count', type=int, default=10000)
    p.add_argument('--mesh', choices=('icosphere', 'box'), default='icosphere')
    p.add_argument('--subdivisions', type=int, default=2, help='icosphere subdivisions (default 2: 320 triangles)')
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--spacing', type=float, default=3.0, help='grid cell size (the mesh has radius 1)')
    p.add_argument('--uniform-scale', action='store_true', help='the same scale on all three axes')
    p.add_argument('--required', action='store_true', help='also list the extension in extensionsRequired')
    p.add_argument('--single', metavar='ONE.glb', help='also write the mesh at one plain node')
    p.add_argument('--nodes', metavar='NODES.glb', help='also write the placements as plain nodes')
    p.set_defaults(func=cmd_gpu)
    args = parser.parse_args()
    if args.count < 1:
        parser.error('--count must be at least 1')
    args.func(args)


if __name__ == '__main__':
    main()
