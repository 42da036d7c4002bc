#!/usr/bin/env python3
"""Recreates the regression files of tests/fuzz/regressions/ byte by byte.

Each file is one input of a fuzz target, in that target's input format
(docs/fuzzing.md); regressions/cases.txt says what each must do. Run from
anywhere: python3 tests/fuzz/make_regressions.py. Files found by the fuzzer
itself (crash-*, and the JPEG cases) are kept as they were found, not made here.
"""
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "regressions")
SEP = b"\n%%\n"  # part separator of the course_txt and obj targets
IMAGE_EXT = [".bmp", ".png", ".tga", ".jpg", ".jpeg", ".hdr", ".gif", ".ppm", ".pgm", ".psd", ".exr", ".tif"]


def put(target, name, data):
    os.makedirs(os.path.join(OUT, target), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(OUT, target, name), "wb") as f:
        f.write(data)


def image_input(ext, data):
    return bytes([IMAGE_EXT.index(ext)]) + data


# 23-byte RLE TGA declaring 23170 x 23170 32-bit pixels (2.1 GB decoded, just
# under 2^31 bytes, so no size check of stb's trips): 18-byte header, then one
# run packet of 128 pixels; at the end of the file stb reads zeros, i.e. more
# 1-pixel raw packets, until the whole image is filled.
TGA_HUGE = struct.pack("<BBBHHBHHHHBB", 0, 0, 10, 0, 0, 0, 0, 0, 23170, 23170, 32, 0x28) + bytes([0xFF, 1, 2, 3, 255])
assert len(TGA_HUGE) == 23

# RLE Radiance .hdr whose first scanline has a run count of 0: stb's loop
# `while ((nleft = width - i) > 0)` never advances (stb v2.27 checks count >
# nleft, not count == 0), and past the end of the file every byte reads 0.
HDR_HEADER = b"#?RADIANCE\n# rayform fuzz regression: zero-length RLE run\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 64\n"
HDR_ZERO_RUN = HDR_HEADER + bytes([2, 2, 0, 64]) + bytes([0]) * 2



def jpeg(sof, width, quant16, scan, entropy):
    """A one-component JPEG: 16-bit (quant16) or 8-bit quantisation table 0
    of 65535s (255s), DC table 0 with one 1-bit code for category 15, AC table
    0 with one 1-bit code for end-of-block, frame type `sof` (0xC0 baseline,
    0xC2 progressive) of width x 8 pixels, one scan (Ss, Se, Ah<<4|Al) over
    `entropy` (already byte-stuffed)."""
    def seg(marker, body):
        return bytes([0xFF, marker]) + struct.pack(">H", len(body) + 2) + body
    dqt = bytes([0x10 if quant16 else 0x00]) + (b"\xff\xff" * 64 if quant16 else b"\xff" * 64)
    sof_body = bytes([8]) + struct.pack(">HH", 8, width) + bytes([1, 1, 0x11, 0])
    dht = bytes([0x00, 1] + [0] * 15 + [15]) + bytes([0x10, 1] + [0] * 15 + [0])
    sos = bytes([1, 1, 0x00]) + bytes(scan)
    return (b"\xff\xd8" + seg(0xDB, dqt) + seg(sof, sof_body) + seg(0xC4, dht) + seg(0xDA, sos) + entropy
            + b"\xff\xd9")


def dc_blocks(count, with_eob):
    """`count` blocks whose DC difference is +32767 (code 0, then fifteen 1
    bits), each followed by an end-of-block code when `with_eob`; padded with
    1 bits and byte-stuffed."""
    bits = ("0" + "1" * 15 + ("0" if with_eob else "")) * count
    bits += "1" * (-len(bits) % 8)
    out = bytearray()
    for i in range(0, len(bits), 8):
        out.append(int(bits[i:i + 8], 2))
        if out[-1] == 0xFF:
            out.append(0)
    return bytes(out)


# Baseline JPEG, 16-bit quantiser 65535: the second block's DC is 65534, and
# stb's `dc * dequant[0]` (stbi__jpeg_decode_block) overflows int.
JPEG_DC_OVERFLOW = jpeg(0xC0, 16, True, [0, 63, 0x00], dc_blocks(2, True))
# Progressive JPEG, DC scan with successive approximation Al = 13: stb's
# `dc * (1 << j->succ_low)` (stbi__jpeg_decode_block_prog_dc) overflows int
# from the ninth block (9 * 32767 << 13 > 2^31).
JPEG_PROG_DC_SHIFT = jpeg(0xC2, 80, False, [0, 0, 0x0D], dc_blocks(10, False))

OBJ_TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"


def gltf(doc):
    return json.dumps(doc, separators=(",", ":"))


def gltf_with_buffer(uri, byte_length):
    """A triangle whose positions come from buffer `uri`."""
    return gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [-1e9, -1e9, -1e9], "max": [1e9, 1e9, 1e9]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": byte_length, "uri": uri}],
    })


def two_parent_graph(levels):
    """Two nodes per level, each the child of both nodes of the level above:
    every node below the top has two parents, and there are 2^levels paths."""
    nodes = []
    for level in range(levels):
        children = [2 * level + 2, 2 * level + 3]
        nodes += [{"children": children}, {"children": children}]
    nodes += [{"mesh": 0}, {"mesh": 0}]
    return gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}], "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,"
                     "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    })


def glb(json_text, bin_data):
    j = json_text.encode()
    j += b" " * (-len(j) % 4)
    b = bin_data + b"\0" * (-len(bin_data) % 4)
    body = struct.pack("<I4s", len(j), b"JSON") + j
    if b:
        body += struct.pack("<I4s", len(b), b"BIN\0") + b
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def main():
    # ---- image: the first byte picks the extension --------------------------
    put("image", "tga_rle_23170x23170.bin", image_input(".tga", TGA_HUGE))
    put("image", "hdr_rle_zero_run.bin", image_input(".hdr", HDR_ZERO_RUN))
    put("image", "jpeg_dc_dequant_overflow.bin", image_input(".jpg", JPEG_DC_OVERFLOW))
    put("image", "jpeg_progressive_dc_shift_overflow.bin", image_input(".jpg", JPEG_PROG_DC_SHIFT))

    # ---- obj: model.obj %% model.mtl %% texture (tex.tga, tex.bmp, ... name it) ---
    put("obj", "map_kd_tga_23170x23170.obj", (OBJ_TRIANGLE + "mtllib model.mtl\nusemtl big\nf 1/1 2/2 3/3\n").encode()
        + SEP + b"newmtl big\nKd 1 1 1\nmap_Kd tex.tga\n" + SEP + TGA_HUGE)
    put("obj", "mtllib_outside.obj", OBJ_TRIANGLE + "mtllib ../outside/x.mtl\nusemtl bait_outside\nf 1/1 2/2 3/3\n")
    put("obj", "map_kd_outside.obj", (OBJ_TRIANGLE + "mtllib model.mtl\nusemtl m\nf 1/1 2/2 3/3\n").encode()
        + SEP + b"newmtl m\nKd 1 1 1\nmap_Kd ../outside/x.bmp\n")
    # 10 million identical triangles (80 MB): expanded by the replay runner.
    put("obj", "ten_million_identical_triangles.repeat",
        "repeat 10000000\nv 0 0 0\nv 1 0 0\nv 0 1 0\n--body--\nf 1 2 3\n")
    # 100 MB of zero bytes: no line end, no face (issue 33's 2 GB file, smaller).
    put("obj", "zeros_100mb.repeat", b"repeat 104857600\n--body--\n\0")

    # ---- course_txt: scene.txt %% mesh.obj %% texture ------------------------
    camera = "PerspectiveCamera {\n center 0 0 5\n direction 0 0 -1\n up 0 1 0\n angle 30\n}\n"
    lights = "Lights {\n numLights 1\n DirectionalLight {\n direction 0 0 -1\n color 1 1 1\n }\n}\n"
    background = "Background {\n color 0 0 0\n ambientLight 0.1 0.1 0.1\n}\n"

    def course(material, objects):
        return (camera + lights + background + "Materials {\n numMaterials 1\n" + material + "}\n"
                + "Group {\n numObjects 1\n MaterialIndex 0\n" + objects + "}\n")

    plain = "PhongMaterial {\n diffuseColor 1 1 1\n}\n"
    put("course_txt", "obj_file_dev_zero.txt", course(plain, "TriangleMesh {\n obj_file /dev/zero\n}\n"))
    put("course_txt", "obj_file_outside.txt", course(plain, "TriangleMesh {\n obj_file ../outside/x.obj\n}\n"))
    put("course_txt", "texture_outside.txt",
        course("PhongMaterial {\n diffuseColor 1 1 1\n texture ../outside/x.bmp\n}\n",
               "TriangleMesh {\n obj_file mesh.obj\n}\n").encode()
        + SEP + (OBJ_TRIANGLE + "f 1/1 2/2 3/3\n").encode())

    # ---- gltf: one file (.glb when it starts with "glTF") -------------------
    put("gltf", "extras_nested_20000.gltf",
        '{"asset":{"version":"2.0","extras":' + "[" * 20000 + "]" * 20000 + '},"scenes":[{"nodes":[]}]}')
    put("gltf", "two_parents_40_levels.gltf", two_parent_graph(40))
    put("gltf", "two_parents_24_levels.gltf", two_parent_graph(24))
    # An accessor of 2e8 VEC3 floats without a bufferView (all zeros by the
    # specification): 2.4 GB once read.
    huge = gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"componentType": 5126, "count": 200000000, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]}],
    })
    put("gltf", "glb_accessor_count_2e8_no_view.glb", glb(huge, b""))
    put("gltf", "buffer_uri_etc_passwd.gltf", gltf_with_buffer("../../../../etc/passwd", 36))
    # Counts the file does not back (issue 33): zeros without a bufferView.
    # POSITION of 134217723 elements, just under the vertex limit (1.6 GB).
    put("gltf", "position_134217723_no_view.gltf", gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"componentType": 5126, "count": 134217723, "type": "VEC3",
                       "min": [0, 0, 0], "max": [0, 0, 0]}],
    }))
    # EXT_mesh_gpu_instancing: 2^25 translations without a bufferView (2 GB of matrices).
    put("gltf", "instancing_2e25_no_view.gltf", gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "extensionsUsed": ["EXT_mesh_gpu_instancing"],
        "nodes": [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 1}}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"componentType": 5126, "count": 1 << 25, "type": "VEC3"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,"
                     "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    }))
    # 64 nodes with their own morph weights over a mesh of 2^21 vertices
    # without a bufferView: 64 copies (2.15 GB).
    put("gltf", "morph_64_nodes_2e21_no_view.gltf", gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(64))}],
        "nodes": [{"mesh": 0, "weights": [(k + 1) / 64]} for k in range(64)],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "targets": [{"POSITION": 1}]}]}],
        "accessors": [{"componentType": 5126, "count": 1 << 21, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]},
                      {"componentType": 5126, "count": 1 << 21, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}],
    }))
    # A Draco attribute id of 2^40, which tinygltf reads as 0.
    put("gltf", "draco_attribute_id_2e40.gltf", gltf({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "extensions": {"KHR_draco_mesh_compression": {
            "bufferView": 0, "attributes": {"POSITION": 1 << 40}}}}]}],
        "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 16}],
        "buffers": [{"byteLength": 16, "uri": "data:application/octet-stream;base64,RFJBQ08CAgEBAAAACQkJCQ=="}],
    }))
    put("gltf", "buffer_uri_outside.gltf", gltf_with_buffer("../outside/x.bin", 144))

    # ---- course_args: words split at NUL or white space ---------------------
    put("course_args", "size_20000x20000.txt", "-input scene.txt -size 20000 20000 -output out.bmp\n")
    put("course_args", "size_100000x100000.txt", "-input scene.txt -size 100000 100000 -output out.bmp\n")


if __name__ == "__main__":
    main()
